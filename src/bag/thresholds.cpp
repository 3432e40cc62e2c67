#include "virtual_go/bag/thresholds.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {
namespace bag {
namespace {

std::string format_short(double v) {
  std::ostringstream out;
  out.precision(3);
  out << v;
  return out.str();
}

// The contact integrator's dense output between its (guarded) step ends may lie 1.6e-12 relative
// above an earlier sample (docs/physics.md, "World"); 1e-11 leaves round-off room and still
// catches any real gain. The gap bound is the World's own promise (gap >= -1e-12 m). Jellett's
// integral is held to 7e-13 through flight, cap impacts and sliding; 1e-9 is the floor of every
// other figure. A resting stone is frozen bit for bit: no sample may differ.
const ContactLimit kContactLimits[kContactLimitCount] = {
    {"energy rise", "--max-energy-rise", 1e-11, "relative",
     "contact segments: energy above the segment's lowest so far / its energy scale"},
    {"penetration (m)", "--max-penetration", 1e-12, "m",
     "every sample: depth of the lens below the board's top or the table (< 0: clear)"},
    {"Jellett drift", "--max-jellett-drift", 1e-9, "relative",
     "|J - J0| / (R max|L|): flights; cap contact when l_r = l_s = 0"},
    {"rest motion", "--max-rest-moves", 0.0, "samples",
     "rest segments: samples not bitwise equal to the first or not at zero velocity"},
    {"stone overlap (m)", "--max-overlap", 1e-9, "m",
     "two stones of one ~stones message: penetration depth of the two lenses (< 0: apart)"},
};

}  // namespace

const ContactLimit& contact_limit(int index) { return kContactLimits[index]; }

std::string default_limits_text() {
  std::ostringstream out;
  out << "default limits (h = dt, w = largest |omega| of the segment, T = its duration;\n"
      << "p and K from the table below, by the integrator named in ~info):\n"
      << "  orientation error  " << kBoundFloor << " rad + K_q (h w)^p w T\n"
      << "  energy drift       " << kBoundFloor << " + K_E (h w)^p (1 + w T)\n"
      << "  position error     " << kBoundFloor << " m + " << kPositionRoundOff
      << " |x| + K_g |g| h T / 2\n"
      << "  momentum drift     " << kBoundFloor << "\n"
      << "  | |q| - 1 |        " << kBoundFloor << "\n\n"
      << "  " << std::left << std::setw(12) << "integrator" << std::setw(4) << "p" << std::setw(8)
      << "K_q" << std::setw(8) << "K_E"
      << "K_g\n";
  for (const IntegratorInfo& i : integrators().entries()) {
    const ErrorBoundConstants& k = i.error_bound;
    out << "  " << std::left << std::setw(12) << i.name << std::setw(4) << i.order << std::setw(8)
        << k.k_orientation << std::setw(8) << k.k_energy << k.k_gravity << "\n";
  }
  out << "\ncontact checks (with the board in ~info; each limit set by its option):\n";
  for (const ContactLimit& c : kContactLimits) {
    out << "  " << std::left << std::setw(18) << c.figure << std::setw(7) << c.default_limit
        << std::setw(9) << c.unit << std::setw(22) << c.option << "\n"
        << "      " << c.meaning << "\n";
  }
  return out.str();
}

PhysicsBounds physics_bounds(const std::string& integrator, double dt_s,
                             const SegmentResult& segment, double gravity_norm,
                             const LimitOverrides& overrides) {
  PhysicsBounds b;
  const bool all_overridden = overrides.orientation_error && overrides.position_error &&
                              overrides.energy_drift && overrides.momentum_drift;
  const IntegratorInfo* info = find_integrator(integrator);
  if (info == nullptr && !all_overridden) {
    throw InvalidArgument("integrator", "unknown integrator " + quote_user_text(integrator) +
                                            " in ~info (known: " + join(integrator_names(), " ") +
                                            "); pass --max-orientation-error, "
                                            "--max-position-error, --max-energy-drift and "
                                            "--max-momentum-drift");
  }
  const ErrorBoundConstants k = info ? info->error_bound : ErrorBoundConstants{};
  const double w = segment.max_angular_speed_radps, t = segment.duration_s;
  const double hw_p = info && info->order > 0 ? std::pow(dt_s * w, info->order) : 0.0;
  b.orientation_error = kBoundFloor + k.k_orientation * hw_p * w * t;
  b.energy_drift = kBoundFloor + k.k_energy * hw_p * (1.0 + w * t);
  b.momentum_drift = kBoundFloor;
  b.position_error = kBoundFloor + kPositionRoundOff * segment.max_abs_position +
                     k.k_gravity * 0.5 * gravity_norm * dt_s * t;
  b.quat_norm_error = kBoundFloor;
  b.basis = integrator + ", dt " + format_short(dt_s) + " s, |w| " + format_short(w) +
            " rad/s, T " + format_short(t) + " s";

  if (overrides.orientation_error) b.orientation_error = *overrides.orientation_error;
  if (overrides.position_error) b.position_error = *overrides.position_error;
  if (overrides.energy_drift) b.energy_drift = *overrides.energy_drift;
  if (overrides.momentum_drift) b.momentum_drift = *overrides.momentum_drift;
  if (overrides.quat_norm_error) b.quat_norm_error = *overrides.quat_norm_error;
  return b;
}

std::vector<Check> run_checks(const Recording& recording, const std::vector<StampStatistics>& stats,
                              const PhysicsResult* physics, const LimitOverrides& overrides,
                              const std::vector<StonePhysics>& stones,
                              const StoneOverlapResult* overlap, const StoneIslandResult* islands) {
  std::vector<Check> checks;
  auto add = [&](std::string figure, std::string subject, double value, double limit,
                 std::string basis) {
    // !(value > limit) would pass a NaN; a figure that could not be computed fails.
    const bool pass = std::isfinite(value) && value <= limit;
    checks.push_back({std::move(figure), std::move(subject), value, limit, pass, std::move(basis)});
  };

  // The /tf rows of the stones of ~stones: one check per figure over all of them (a game has
  // hundreds), naming the first row at fault.
  std::size_t stone_rows = 0, repeated = 0, non_increasing = 0;
  std::string first_repeated, first_non_increasing;
  for (std::size_t i = 0; i < recording.topics.size() && i < stats.size(); ++i) {
    const TopicStamps& topic = recording.topics[i];
    const StampStatistics& s = stats[i];
    if (topic.aperiodic || !topic.header_stamps) continue;
    if (topic.on_change) {
      ++stone_rows;
      if (first_repeated.empty() && !s.repeated.empty()) first_repeated = topic.topic;
      if (first_non_increasing.empty() && !s.non_increasing.empty()) {
        first_non_increasing = topic.topic;
      }
      repeated += s.repeated.size();
      non_increasing += s.non_increasing.size();
      continue;
    }
    add("repeated stamps", topic.topic, static_cast<double>(s.repeated.size()), 0.0,
        "stamps must strictly increase");
    add("non-increasing stamps", topic.topic, static_cast<double>(s.non_increasing.size()), 0.0,
        "stamps must strictly increase");
    add("gaps > 2x period", topic.topic, static_cast<double>(s.gaps.size()),
        static_cast<double>(overrides.max_gaps), "--max-gaps");
    if (topic.at_node_rate && recording.info && recording.info->rate_hz > 0.0 && s.count > 1) {
      add("mean rate deviation", topic.topic,
          std::abs(s.mean_rate_hz / recording.info->rate_hz - 1.0), overrides.rate_tolerance,
          "relative to ~info rate " + format_short(recording.info->rate_hz) +
              " Hz, --rate-tolerance");
    }
  }

  if (stone_rows > 0) {
    const std::string rows = "/tf of " + std::to_string(stone_rows) + " stones";
    add("repeated stamps", rows, static_cast<double>(repeated), 0.0,
        first_repeated.empty() ? "stamps must strictly increase" : "first in " + first_repeated);
    add("non-increasing stamps", rows, static_cast<double>(non_increasing), 0.0,
        first_non_increasing.empty() ? "stamps must strictly increase"
                                     : "first in " + first_non_increasing);
  }

  const double overlap_limit = overrides.contact[kOverlap] ? *overrides.contact[kOverlap]
                                                           : contact_limit(kOverlap).default_limit;
  if (overlap != nullptr && std::isfinite(overlap->min_gap_m)) {
    std::ostringstream basis;
    basis << contact_limit(kOverlap).option << ", m; at " << std::fixed << std::setprecision(6)
          << to_seconds(overlap->stamp_ns) << " s; "
          << std::count_if(overlap->overlaps.begin(), overlap->overlaps.end(),
                           [&](const PairOverlap& o) { return o.depth_m > overlap_limit; })
          << " pairs over the limit";
    add(contact_limit(kOverlap).figure, "stones " + overlap->stone_a + ", " + overlap->stone_b,
        -overlap->min_gap_m, overlap_limit, basis.str());
  }
  if (islands != nullptr && !islands->islands.empty()) {
    // The island's total energy is held to the per-stone contact limit, relative to the summed
    // energy scale as a stone's is to its own.
    const double limit = overrides.contact[kEnergyRise] ? *overrides.contact[kEnergyRise]
                                                        : contact_limit(kEnergyRise).default_limit;
    const StoneIsland& w = islands->islands[islands->worst];
    std::ostringstream basis;
    basis << contact_limit(kEnergyRise).option << ", relative to the members' summed scale; at "
          << std::fixed << std::setprecision(6) << to_seconds(w.worst_stamp_ns) << " s; "
          << islands->islands.size() << " islands, "
          << std::count_if(islands->islands.begin(), islands->islands.end(),
                           [&](const StoneIsland& i) { return !(i.max_energy_rise <= limit); })
          << " over the limit";
    add("island energy rise", "island of stones " + join(w.members, ", "), w.max_energy_rise, limit,
        basis.str());
  }
  if (!recording.info || (physics == nullptr && stones.empty())) return checks;
  // A message with a NaN or infinity has no figures, and the maxima skip NaN: the count
  // itself has to fail --strict.
  auto add_non_finite = [&](const NonFiniteValues& v, const std::string& topic) {
    std::string basis = "every value finite";
    if (v.count > 0) {
      std::ostringstream first;
      first << std::fixed << std::setprecision(6) << to_seconds(v.first_stamp_ns);
      basis = "first at " + first.str() + " s, " + v.first_field + "; no figures for them";
    }
    add("non-finite values", topic, static_cast<double>(v.count), 0.0, basis);
  };
  if (physics != nullptr) {
    add_non_finite(physics->non_finite_odom, recording.odom_topic);
    if (!recording.events.empty()) {
      add_non_finite(physics->non_finite_events, recording.events_topic);
    }
  }
  if (!stones.empty()) {
    NonFiniteValues samples, events;
    auto sum = [](NonFiniteValues& total, const NonFiniteValues& v) {
      if (v.count > 0 && (total.count == 0 || v.first_stamp_ns < total.first_stamp_ns)) {
        total.first_stamp_ns = v.first_stamp_ns;
        total.first_field = v.first_field;
      }
      total.count += v.count;
    };
    for (const StonePhysics& s : stones) {
      if (!s.physics) {
        add("stone checked", "stone " + s.name, NAN, 0.0, s.note);
        continue;
      }
      sum(samples, s.physics->non_finite_odom);
      sum(events, s.physics->non_finite_events);
    }
    add_non_finite(samples, recording.stones_topic + " and /tf");
    if (!recording.events.empty()) add_non_finite(events, recording.events_topic + " (stones)");
  }
  // Per figure, the segment closest to (or furthest over) its own limit, and every other
  // segment over it (a violation is named per segment, with its numbers).
  constexpr int kFlightFigures = 5;
  constexpr int kFigures = kFlightFigures + kContactLimitCount;
  struct Worst {
    bool seen = false;
    double ratio = 0.0;
    Check check;
  };
  Worst worst[kFigures];
  std::vector<Check> over;  // segments over a limit, other than the worst
  const char* names[kFlightFigures] = {"max | |q| - 1 |", "energy drift", "momentum drift",
                                       "orientation error (rad)", "position error (m)"};
  // Segments of every stone compete for the worst of each figure; with several stones a
  // segment's subject names its stone.
  struct Checked {
    const PhysicsResult* physics;
    const RecordingInfo* info;
    std::string prefix;
  };
  std::vector<Checked> checked;
  if (physics != nullptr) {
    checked.push_back({physics, &*recording.info,
                       stones.empty() ? "" : "stone " + recording.info->stone_frame + " "});
  }
  for (const StonePhysics& s : stones) {
    if (s.physics) checked.push_back({&*s.physics, &s.info, "stone " + s.name + " "});
  }
  for (const Checked& stone : checked) {
    const RecordingInfo& info = *stone.info;
    for (std::size_t k = 0; k < stone.physics->segments.size(); ++k) {
      const SegmentResult& seg = stone.physics->segments[k];
      if (seg.samples == 0) continue;
      PhysicsBounds b;
      try {
        b = physics_bounds(info.integrator, info.dt_s, seg, info.gravity_world.norm(), overrides);
      } catch (const InvalidArgument& e) {
        add("physics bound", stone.prefix + "segment " + std::to_string(k), NAN, 0.0, e.what());
        return checks;
      }
      const bool flight = seg.kind == SegmentKind::flight;
      const bool rest = seg.kind == SegmentKind::rest;
      // What each figure is for this segment; NaN computes nothing, `applies` false skips it.
      double values[kFigures] = {seg.max_quat_norm_error,
                                 seg.max_energy_drift,
                                 seg.max_momentum_drift,
                                 seg.predicted ? seg.max_orientation_error : NAN,
                                 seg.predicted ? seg.max_position_error : NAN,
                                 seg.max_energy_rise,
                                 -seg.min_gap_m,
                                 seg.max_jellett_drift,
                                 static_cast<double>(seg.rest_moved),
                                 NAN};
      const bool applies[kFigures] = {true,           flight || rest,
                                      flight || rest, flight,
                                      flight,         seg.kind == SegmentKind::contact,
                                      seg.board,      seg.jellett_conserved,
                                      rest,           false};  // overlap: per pair of stones, below
      double limits[kFigures] = {b.quat_norm_error, b.energy_drift, b.momentum_drift,
                                 b.orientation_error, b.position_error};
      for (int c = 0; c < kContactLimitCount; ++c) {
        limits[kFlightFigures + c] =
            overrides.contact[c] ? *overrides.contact[c] : contact_limit(c).default_limit;
      }
      const std::string kind = " (" + segment_kind_name(seg.kind) + ", " + seg.plan.reason + ")";
      for (int f = 0; f < kFigures; ++f) {
        if (!applies[f]) continue;
        double ratio = INFINITY;  // a figure that could not be computed is the worst
        if (std::isfinite(values[f])) {
          // A clearance (negative penetration) gives a negative ratio: the smallest is the worst.
          ratio = limits[f] > 0.0 ? values[f] / limits[f]
                                  : (values[f] > limits[f] ? INFINITY : values[f] - limits[f]);
        }
        std::string basis;
        if (f == 0) {
          basis = "a published quaternion is unit";
        } else if (f < kFlightFigures) {
          basis = seg.predicted || f < 3 ? b.basis : seg.note;
        } else {
          const ContactLimit& c = contact_limit(f - kFlightFigures);
          basis = std::string(c.option) + ", " + c.unit;
          if (f - kFlightFigures == kRestMoves && seg.rest_moved > 0) {
            std::ostringstream moved;
            moved << "; largest move " << seg.rest_max_move_m << " m";
            basis += moved.str();
          }
        }
        const Check check{f < kFlightFigures ? names[f] : contact_limit(f - kFlightFigures).figure,
                          stone.prefix + "segment " + std::to_string(k) + kind,
                          values[f],
                          limits[f],
                          std::isfinite(values[f]) && values[f] <= limits[f],
                          basis};
        if (!worst[f].seen || ratio > worst[f].ratio) {
          if (worst[f].seen && !worst[f].check.pass) over.push_back(worst[f].check);
          worst[f] = {true, ratio, check};
        } else if (!check.pass) {
          over.push_back(check);
        }
      }
    }
  }
  for (const Worst& w : worst) {
    if (w.seen) checks.push_back(w.check);
  }
  for (const Check& c : over) checks.push_back(c);
  return checks;
}

}  // namespace bag
}  // namespace virtual_go
