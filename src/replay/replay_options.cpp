#include "virtual_go/replay/replay_options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>

#include "virtual_go/common/formatting.h"

namespace virtual_go {
namespace replay {

namespace {

// One option: its name, what its value is, its limits, its help line and where it goes.
struct OptionSpec {
  std::string name;
  std::string value;  // e.g. "S"; the unit is in the help
  std::string help;
  double min;
  double max;
  bool integer;
  std::function<void(ReplayOptions&, double)> store;
  std::function<std::string(const ReplayOptions&)> default_text;
};

const std::vector<OptionSpec>& numeric_options() {
  static const std::vector<OptionSpec> table = {
      {"--interval", "S", "wall-clock seconds between moves", 0.0, 3600.0, false,
       [](ReplayOptions& o, double v) { o.interval_s = v; },
       [](const ReplayOptions& o) { return format_value(o.interval_s); }},
      {"--to-move", "N", "the last move to play; 0: only the setup before the first move", 0.0,
       100000.0, true, [](ReplayOptions& o, double v) { o.to_move = static_cast<int>(v); },
       [](const ReplayOptions&) { return std::string("the whole game"); }},
      {"--drop-height", "H",
       "m from the board's top face to each stone's lowest point; 0: set down at rest", 0.0, 1.0,
       false, [](ReplayOptions& o, double v) { o.drop_height_m = v; },
       [](const ReplayOptions& o) { return format_value(o.drop_height_m); }},
      {"--timeout", "S", "seconds to wait for the node's services", 0.0, 3600.0, false,
       [](ReplayOptions& o, double v) { o.timeout_s = v; },
       [](const ReplayOptions& o) { return format_value(o.timeout_s); }},
  };
  return table;
}

double number(const OptionSpec& spec, const std::string& text) {
  const std::string at = spec.name + " " + quote_user_text(text);
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
    throw UsageError(at + ": not a number");
  }
  if (spec.integer && v != std::floor(v)) throw UsageError(at + ": not a whole number");
  if (v < spec.min || v > spec.max) {
    throw UsageError(at + ": must be between " + format_value(spec.min) + " and " +
                     format_value(spec.max));
  }
  return v;
}

}  // namespace

const std::vector<ExitCodeText>& exit_codes() {
  static const std::vector<ExitCodeText> table = {
      {kExitOk, "the game was replayed"},
      {kExitServiceFailed, "a service call failed or was refused mid-replay (what was done stays)"},
      {kExitUsage, "bad command line"},
      {kExitBadRecord,
       "the game record cannot be read or is malformed, or has no move --to-move (nothing was "
       "called)"},
      {kExitNoServices, "the node's services did not appear within --timeout (nothing was called)"},
      {kExitInterrupted, "interrupted (Ctrl-C, ROS shutdown) before the end"},
  };
  return table;
}

const std::vector<OptionText>& option_texts() {
  static const std::vector<OptionText> table = [] {
    const ReplayOptions defaults;
    std::vector<OptionText> rows;
    for (const OptionSpec& o : numeric_options()) {
      rows.push_back({o.name + " " + o.value, o.help,
                      format_value(o.min) + " to " + format_value(o.max),
                      o.default_text(defaults)});
    }
    rows.push_back({"--node NAME",
                    "the stone node whose NAME/clear, NAME/place and NAME/remove are called", "",
                    defaults.node});
    rows.push_back({"-h, --help", "this text", "", ""});
    return rows;
  }();
  return table;
}

std::string replay_usage() {
  std::ostringstream out;
  out << "usage: rosrun virtual_go sgf_replay GAME.sgf [options]\n"
         "\n"
         "Replays the main line of an SGF game record (19 x 19, FF[3] or FF[4]) onto the board of\n"
         "a running stone node: reads the whole file first (a malformed file: an error naming the\n"
         "line, nothing placed), calls the node's ~clear, then for each move ~place (the stone\n"
         "dropped at its point) and ~remove for the stones it captures (Go's rules: the\n"
         "opponent's groups without liberties, then suicide). Setup stones (AB, AW, AE) are\n"
         "placed and removed likewise; passes place nothing.\n"
         "\n"
         "options:\n";
  for (const OptionText& o : option_texts()) {
    out << "  " << o.option << std::string(o.option.size() < 18 ? 18 - o.option.size() : 1, ' ')
        << o.meaning;
    if (!o.range.empty()) out << " (" << o.range;
    if (!o.default_value.empty())
      out << (o.range.empty() ? " (" : "; ") << "default " << o.default_value;
    if (!o.range.empty() || !o.default_value.empty()) out << ")";
    out << "\n";
  }
  out << "\nexit codes:\n";
  for (const ExitCodeText& e : exit_codes()) out << "  " << e.code << "  " << e.meaning << "\n";
  return out.str();
}

ReplayOptions parse_replay_options(const std::vector<std::string>& args) {
  ReplayOptions o;
  for (std::size_t k = 0; k < args.size(); ++k) {
    std::string a = args[k];
    if (a == "-h" || a == "--help") {
      o.help = true;
      continue;
    }
    if (a.rfind("--", 0) != 0 || a == "--") {
      if (!o.game_path.empty()) {
        throw UsageError("one game record only: got " + quote_user_text(o.game_path) + " and " +
                         quote_user_text(a));
      }
      o.game_path = a;
      continue;
    }
    // --name=value or --name value
    std::string value;
    bool has_value = false;
    const std::size_t eq = a.find('=');
    if (eq != std::string::npos) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
      has_value = true;
    }
    auto take_value = [&]() -> std::string {
      if (has_value) return value;
      if (k + 1 >= args.size()) throw UsageError(a + ": needs a value");
      return args[++k];
    };
    if (a == "--node") {
      o.node = take_value();
      if (o.node.empty()) throw UsageError("--node: needs a node name");
      continue;
    }
    bool known = false;
    for (const OptionSpec& spec : numeric_options()) {
      if (spec.name != a) continue;
      spec.store(o, number(spec, take_value()));
      known = true;
    }
    if (!known) throw UsageError("unknown option " + quote_user_text(a) + " (see --help)");
  }
  if (!o.help && o.game_path.empty()) throw UsageError("no game record given (see --help)");
  return o;
}

}  // namespace replay
}  // namespace virtual_go
