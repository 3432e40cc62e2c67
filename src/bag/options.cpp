#include "virtual_go/bag/options.h"

#include <cmath>
#include <cstdlib>

#include "virtual_go/common/formatting.h"

namespace virtual_go {
namespace bag {
namespace {

double parse_limit(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0) {
    throw UsageError(option + " needs a finite number >= 0, got " + quote_user_text(text));
  }
  return v;
}

// The index of a contact limit's option (thresholds.h), or -1.
int contact_option(const std::string& option) {
  for (int c = 0; c < kContactLimitCount; ++c) {
    if (option == contact_limit(c).option) return c;
  }
  return -1;
}

// One line per contact limit, from its table (defaults under "contact checks" below).
std::string contact_options_text() {
  std::string text;
  for (int c = 0; c < kContactLimitCount; ++c) {
    const ContactLimit& limit = contact_limit(c);
    std::string left = std::string("  ") + limit.option + " " + (c == kRestMoves ? "N" : "X");
    left.resize(30, ' ');
    text += left + limit.figure + " limit (" + limit.unit + ")\n";
  }
  return text;
}

}  // namespace

std::string usage_text() {
  // The limits come from the constants in thresholds.cpp, so the two cannot disagree.
  return R"(usage: bag_report BAG [--csv OUT.csv] [--plot OUT.png] [--strict] [options]

Inspects a rosbag recorded from the virtual_go stone node: per topic message count, mean rate,
stamp period p50/p99/max, gaps over 2x the median period, repeated or non-increasing stamps;
physics health from ~odom and ~info, per ~events segment by its regime: flights (| |q| - 1 |,
energy and world angular momentum drift, orientation and position error against the exact
closed form from the event's exact instant, Jellett's integral); contact (slide, roll, rim:
energy never rising, Jellett's integral on a cap without rolling resistance or spinning
friction); rest (every sample bitwise still); with the board in ~info, every sample's gap above
the board's top or the table. Every other stone of ~stones is held to the same checks on its own
~stones states and /tf poses, split at the ~events naming it (a row per stone, checks naming
it), and every pair of stones in one ~stones message must not overlap.

options:
  --csv FILE                  write the physics time series (one row per ~odom message; the
                              stone of ~odom only)
  --plot FILE                 write a PNG of errors and invariants over time (needs gnuplot)
  --strict                    exit 1 when any figure is over its limit
  --node-namespace NS         the node's topics are NS/info, NS/odom, NS/events, NS/stones
                              (default /stone;
                              a topic not found there is taken by message type if unique)
  --max-orientation-error R   rad; default from the integrator in ~info, dt and |w| (see below)
  --max-position-error M      m
  --max-energy-drift X        relative to the segment's energy scale
  --max-momentum-drift X      relative to |L0|
  --max-quat-norm-error X     (defaults below)
)" + contact_options_text() +
         R"(  --max-gaps N                gaps allowed per periodic topic (default 0)
  --rate-tolerance X          allowed |mean rate / ~info rate - 1| (default 0.1)
  -h, --help                  this text

)" + default_limits_text() +
         R"(
exit codes: 0 ok; 1 --strict and a figure over its limit; 2 bad command line; 3 bag unreadable
(missing, not a bag, truncated); 4 partial report (empty bag, no ~info or ~odom, reading stopped
early); 5 --csv or --plot could not be written.
)";
}

Options parse_options(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--csv") {
      o.csv_path = value();
    } else if (a == "--plot") {
      o.plot_path = value();
    } else if (a == "--strict") {
      o.strict = true;
    } else if (a == "--node-namespace") {
      o.node_namespace = value();
    } else if (a == "--max-orientation-error") {
      o.limits.orientation_error = parse_limit(a, value());
    } else if (a == "--max-position-error") {
      o.limits.position_error = parse_limit(a, value());
    } else if (a == "--max-energy-drift") {
      o.limits.energy_drift = parse_limit(a, value());
    } else if (a == "--max-momentum-drift") {
      o.limits.momentum_drift = parse_limit(a, value());
    } else if (a == "--max-quat-norm-error") {
      o.limits.quat_norm_error = parse_limit(a, value());
    } else if (const int c = contact_option(a); c >= 0) {
      o.limits.contact[c] = parse_limit(a, value());
    } else if (a == "--max-gaps") {
      const double n = parse_limit(a, value());
      if (n != std::floor(n)) throw UsageError("--max-gaps needs a whole number");
      o.limits.max_gaps = static_cast<std::size_t>(n);
    } else if (a == "--rate-tolerance") {
      o.limits.rate_tolerance = parse_limit(a, value());
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option " + a + " (see --help)");
    } else if (o.bag_path.empty()) {
      o.bag_path = a;
    } else {
      throw UsageError("more than one bag given: " + o.bag_path + " and " + a);
    }
  }
  if (!o.help && o.bag_path.empty()) throw UsageError("no bag given (see --help)");
  return o;
}

}  // namespace bag
}  // namespace virtual_go
