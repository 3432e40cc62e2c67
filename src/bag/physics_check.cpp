#include "virtual_go/bag/physics_check.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/go/board_distance.h"

namespace virtual_go {
namespace bag {
namespace {

// The board of ~info as the core's distance, or nothing (no board, or ~info cannot describe one:
// the note says why).
std::optional<BoardDistance> board_of(const RecordingInfo& info, std::string& note) {
  if (!info.board_enabled) return std::nullopt;
  try {
    BoardGeometry board;
    board.size_x_m = info.board_size_m.x();
    board.size_y_m = info.board_size_m.y();
    board.thickness_m = info.board_size_m.z();
    validate_board("info board_size", board);
    return BoardDistance(LensGeometry(LensShape(info.width_m, info.height_m)), board);
  } catch (const std::exception& e) {
    note = std::string("no gap check: ~info's board or lens is unusable: ") + e.what();
    return std::nullopt;
  }
}

// Jellett's integral of the cap facing the plane below (docs/physics.md, "Sustained contact"):
// J = L . (R e_z - s d b), s = +1 for the bottom cap (b . e_z > 0), -1 for the top cap. In
// flight it is conserved for either sign (L and L . b are).
double jellett(const LensGeometry& lens, const RigidBodyState& s, double cap_sign) {
  const Eigen::Vector3d b = s.orientation * Eigen::Vector3d::UnitZ();
  return s.angular_momentum_world.dot(lens.sphere_radius() * Eigen::Vector3d::UnitZ() -
                                      cap_sign * lens.sphere_offset() * b);
}

bool is_fallback_detail(const std::string& detail) {
  // The World's nonsmooth fallback (edges, corners, sides) starts with these details; it
  // applies neither a rolling couple nor a cap's geometry, so Jellett's integral does not hold.
  return detail == "edge_contact" || detail == "left_region" || detail == "obstacle";
}

// "the set_state event at 100.500000000 s" or "the first odom at ...".
std::string start_text(const SegmentPlan& plan) {
  return "the " + (plan.from_event ? cut_user_text(plan.reason) + " event" : plan.reason) + " at " +
         stamp_text(plan.start_ns) + " s";
}

}  // namespace

std::string segment_kind_name(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::flight:
      return "flight";
    case SegmentKind::contact:
      return "contact";
    case SegmentKind::rest:
      return "rest";
  }
  return "flight";
}

SegmentKind segment_kind(const std::vector<SegmentEvent>& events, std::size_t index) {
  const EventReason reason = events[index].reason;
  if (reason == EventReason::slide || reason == EventReason::roll || reason == EventReason::rim) {
    return SegmentKind::contact;
  }
  if (reason == EventReason::rest) return SegmentKind::rest;
  if (reason == EventReason::impact && index + 1 < events.size() &&
      events[index + 1].stamp_ns == events[index].stamp_ns &&
      events[index + 1].time_offset_s == events[index].time_offset_s) {
    return SegmentKind::contact;
  }
  return SegmentKind::flight;
}

std::vector<SegmentPlan> plan_segments(const std::vector<OdomSample>& odom,
                                       const std::vector<SegmentEvent>& events) {
  std::vector<SegmentPlan> plans;
  std::size_t next_event = 0;
  auto start_at_event = [&](std::size_t sample_index) {
    SegmentPlan p;
    p.reason = event_reason_name(events[next_event].reason);
    p.detail = events[next_event].detail;
    p.from_event = true;
    p.event_index = next_event;
    p.start_ns = events[next_event].stamp_ns;
    p.start_offset_s = events[next_event].time_offset_s;
    p.first = p.end = sample_index;
    plans.push_back(p);
    ++next_event;
  };
  for (std::size_t i = 0; i < odom.size(); ++i) {
    const std::int64_t stamp = odom[i].stamp_ns;
    while (next_event < events.size()) {
      const std::int64_t event_stamp = events[next_event].stamp_ns;
      const bool jumped_back = !plans.empty() && stamp < plans.back().start_ns;
      // An event after its rounded-down stamp (offset > 0) is still ahead of a sample there.
      const bool reached = event_stamp < stamp ||
                           (event_stamp == stamp && !(events[next_event].time_offset_s > 0.0));
      // Normally an event lies ahead of the current segment's start; after a backwards jump
      // it lies behind it, and the samples have jumped back too.
      if (reached && (plans.empty() || event_stamp >= plans.back().start_ns || jumped_back)) {
        start_at_event(i);
      } else {
        break;
      }
    }
    if (plans.empty() || stamp < plans.back().start_ns) {
      SegmentPlan p;
      p.reason = plans.empty() ? "first odom" : "stamps went backwards (no event)";
      p.start_ns = stamp;
      p.first = p.end = i;
      plans.push_back(p);
    }
    plans.back().end = i + 1;
  }
  while (next_event < events.size()) start_at_event(odom.size());
  return plans;
}

const char* non_finite_field(const OdomSample& sample) {
  if (!sample.position_world.allFinite()) return "position";
  if (!sample.orientation_raw.coeffs().allFinite()) return "orientation";
  if (!sample.velocity_body.allFinite()) return "linear velocity";
  if (!sample.angular_velocity_body.allFinite()) return "angular velocity";
  return nullptr;
}

const char* non_finite_field(const SegmentEvent& event) {
  const RigidBodyState& s = event.state;
  if (!s.position_world.allFinite()) return "position";
  if (!s.orientation.coeffs().allFinite()) return "orientation";
  if (!s.velocity_world.allFinite()) return "linear velocity";
  if (!s.angular_momentum_world.allFinite()) return "angular momentum";
  if (!std::isfinite(event.time_offset_s)) return "time offset";
  return nullptr;
}

RigidBodyState state_from_odom(const MotionModel& model, const OdomSample& sample) {
  // Checked here, not left to RigidBody: its exception would escape check_physics.
  require_finite("odom position", sample.position_world);
  require_finite("odom linear velocity", sample.velocity_body);
  require_finite("odom angular velocity", sample.angular_velocity_body);
  RigidBodyState s;
  s.position_world = sample.position_world;
  s.orientation = require_unit_quaternion("odom orientation", sample.orientation_raw);
  // nav_msgs/Odometry carries the twist in the child (stone) frame.
  s.velocity_world = s.orientation * sample.velocity_body;
  const Eigen::Vector3d omega_world = s.orientation * sample.angular_velocity_body;
  s.angular_momentum_world = model.angular_momentum_world(s.orientation, omega_world);
  return s.validated();  // finite inputs can still overflow L
}

RigidBodyState state_from_event(const SegmentEvent& event) {
  require_finite("event position", event.state.position_world);
  require_finite("event linear velocity", event.state.velocity_world);
  require_finite("event angular momentum", event.state.angular_momentum_world);
  RigidBodyState s = event.state;
  s.orientation = require_unit_quaternion("event orientation", event.state.orientation);
  return s;
}

MotionModel model_from_info(const RecordingInfo& info) {
  require_positive("info mass", info.mass);
  require_positive("info principal_moments.x", info.principal_moments_body.x());
  require_positive("info principal_moments.y", info.principal_moments_body.y());
  require_positive("info principal_moments.z", info.principal_moments_body.z());
  require_finite("info gravity", info.gravity_world);
  return MotionModel(motion_model_from_name(info.model),
                     MassProperties(info.mass, info.principal_moments_body));
}

PhysicsResult check_physics(const RecordingInfo& info, const std::vector<OdomSample>& odom,
                            const std::vector<SegmentEvent>& events) {
  const MotionModel model = model_from_info(info);
  const MotionSetup setup{model, info.gravity_world};
  const double nan = std::numeric_limits<double>::quiet_NaN();

  PhysicsResult result;
  auto count_non_finite = [](NonFiniteValues& counter, const auto& messages) {
    for (const auto& m : messages) {
      const char* field = non_finite_field(m);
      if (field == nullptr) continue;
      if (counter.count++ == 0) {
        counter.first_stamp_ns = m.stamp_ns;
        counter.first_field = field;
      }
    }
  };
  count_non_finite(result.non_finite_odom, odom);
  count_non_finite(result.non_finite_events, events);

  std::string board_note;
  const std::optional<BoardDistance> board = board_of(info, board_note);
  const std::vector<SegmentPlan> plans = plan_segments(odom, events);
  for (std::size_t k = 0; k < plans.size(); ++k) {
    SegmentResult seg;
    seg.plan = plans[k];
    seg.samples = seg.plan.end - seg.plan.first;
    if (!seg.plan.from_event && seg.samples == 0) continue;  // cannot happen; defensive
    seg.kind =
        seg.plan.from_event ? segment_kind(events, seg.plan.event_index) : SegmentKind::flight;
    seg.board = board.has_value();
    seg.min_gap_m = std::numeric_limits<double>::infinity();

    std::optional<RigidBodyState> start;
    try {
      start = seg.plan.from_event ? state_from_event(events[seg.plan.event_index])
                                  : state_from_odom(model, odom[seg.plan.first]);
    } catch (const std::exception& e) {
      seg.note = "unusable start state (" + start_text(seg.plan) + "): " + e.what();
    }
    std::optional<ExactMotion> exact;
    if (start && seg.kind != SegmentKind::flight) {
      // No closed form in contact or at rest: the segment's kind says what it is held to.
    } else if (start) {
      try {
        exact.emplace(setup, *start);
        seg.predicted = true;
      } catch (const std::exception& e) {
        seg.note = "no closed form from " + start_text(seg.plan) + ": " + e.what();
      }
    }

    // The invariants need the segment's own references: its first state's energy and L.
    double e0 = 0.0, scale = 0.0;
    Eigen::Vector3d l0 = Eigen::Vector3d::Zero();
    if (start) {
      const RigidBody body(model, *start);
      e0 = body.total_energy(info.gravity_world);
      scale = energy_scale(body, info.gravity_world);
      l0 = start->angular_momentum_world;
    }
    // Jellett's integral: conserved in flight; in contact on a cap (not the rim, not the
    // fallback) when the surface has neither rolling resistance nor spinning friction.
    double cap_sign = 1.0;
    double j0 = 0.0, j_scale = 0.0;
    if (start && board) {
      const LensGeometry& lens = board->lens();
      const double ct = (start->orientation * Eigen::Vector3d::UnitZ()).z();
      cap_sign = ct >= 0.0 ? 1.0 : -1.0;
      if (seg.kind == SegmentKind::flight) {
        seg.jellett_conserved = true;
      } else if (seg.kind == SegmentKind::contact) {
        const std::string& detail = seg.plan.detail;
        const bool on_table = board->nearest(*start).on_table();
        const double l_r =
            on_table ? info.table_rolling_resistance_m : info.board_rolling_resistance_m;
        const double l_s =
            on_table ? info.table_spinning_friction_m : info.board_spinning_friction_m;
        // Contact segments start at an event (plan_segments).
        const EventReason reason = events[seg.plan.event_index].reason;
        seg.jellett_conserved = reason != EventReason::rim && reason != EventReason::impact &&
                                !is_fallback_detail(detail) &&
                                std::abs(ct) >= lens.cos_cap_cone() && l_r == 0.0 && l_s == 0.0;
      }
      j0 = jellett(lens, *start, cap_sign);
      j_scale = lens.sphere_radius() * start->angular_momentum_world.norm();
      seg.min_gap_m = board->nearest(*start).lens.gap_m;
    }
    double lowest_energy = e0;  // contact: the lowest energy so far (the event's, then samples)
    std::vector<RigidBodyState> states;
    states.reserve(seg.samples);
    // Momentum drift is relative to |L0|. A segment that starts without spin has no such
    // scale: the largest |L| of the segment stands in, so spin appearing from rest reads 1.
    const bool l0_zero = l0.norm() == 0.0;
    double l_scale = l0.norm();
    for (std::size_t i = seg.plan.first; i < seg.plan.end; ++i) {
      try {
        states.push_back(state_from_odom(model, odom[i]));
      } catch (const InvalidArgument&) {
        // A zero quaternion shows in | |q| - 1 |, a non-finite value in non_finite_odom.
        states.push_back(RigidBodyState{});
        states.back().orientation.coeffs().setConstant(nan);
        continue;
      }
      if (!odom[i].has_twist) continue;  // a /tf pose: no velocities, no energy or L
      const RigidBody body(model, states.back());
      scale = std::max(scale, energy_scale(body, info.gravity_world));
      if (l0_zero) l_scale = std::max(l_scale, states.back().angular_momentum_world.norm());
      if (board) {
        j_scale = std::max(
            j_scale, board->lens().sphere_radius() * states.back().angular_momentum_world.norm());
      }
    }
    // Rest: every sample equal to the segment's first to the bit, with zero velocities.
    const OdomSample* rest_reference = seg.samples > 0 ? &odom[seg.plan.first] : nullptr;
    auto same_bits = [](const auto& a, const auto& b) {
      return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
    };

    for (std::size_t j = 0; j < states.size(); ++j) {
      const OdomSample& o = odom[seg.plan.first + j];
      const RigidBodyState& s = states[j];
      PhysicsSample p;
      p.segment = result.segments.size();
      p.stamp_ns = o.stamp_ns;
      p.t_s = seconds_between(seg.plan.start_ns, o.stamp_ns) - seg.plan.start_offset_s;
      p.quat_norm_error = std::abs(o.orientation_raw.norm() - 1.0);
      p.gap_m = p.energy_rise = p.jellett_drift = nan;
      if (seg.kind == SegmentKind::rest && rest_reference != nullptr) {
        const bool still =
            same_bits(o.position_world, rest_reference->position_world) &&
            std::memcmp(o.orientation_raw.coeffs().data(),
                        rest_reference->orientation_raw.coeffs().data(), sizeof(double) * 4) == 0 &&
            (!o.has_twist || ((o.velocity_body.array() == 0.0).all() &&
                              (o.angular_velocity_body.array() == 0.0).all()));
        if (!still) {
          ++seg.rest_moved;
          seg.rest_max_move_m = std::fmax(
              seg.rest_max_move_m, (o.position_world - rest_reference->position_world).norm());
        }
      }
      if (!s.orientation.coeffs().allFinite()) {
        p.energy_drift = p.momentum_drift = p.orientation_error = p.position_error = nan;
        p.angular_speed_radps = nan;
      } else {
        if (board) {
          p.gap_m = board->nearest(s).lens.gap_m;
          seg.min_gap_m = std::fmin(seg.min_gap_m, p.gap_m);
        }
        if (start && board && seg.jellett_conserved && o.has_twist) {
          p.jellett_drift =
              j_scale > 0.0 ? std::abs(jellett(board->lens(), s, cap_sign) - j0) / j_scale : 0.0;
          seg.max_jellett_drift = std::fmax(seg.max_jellett_drift, p.jellett_drift);
        }
        const RigidBody body(model, s);
        p.angular_speed_radps = o.has_twist ? body.angular_velocity_world().norm() : nan;
        if (start && seg.kind == SegmentKind::contact && o.has_twist) {
          const double e = body.total_energy(info.gravity_world);
          p.energy_rise = scale > 0.0 ? (e - lowest_energy) / scale : 0.0;
          lowest_energy = std::min(lowest_energy, e);
          seg.max_energy_rise = std::fmax(seg.max_energy_rise, p.energy_rise);
        }
        if (start && o.has_twist) {
          p.energy_drift =
              scale > 0.0 ? std::abs(body.total_energy(info.gravity_world) - e0) / scale : 0.0;
          p.momentum_drift = l_scale > 0.0 ? (s.angular_momentum_world - l0).norm() / l_scale : 0.0;
        } else {
          // No start state, or a /tf pose (no velocities): held to the closed form and the gap.
          p.energy_drift = p.momentum_drift = nan;
        }
        std::optional<RigidBodyState> predicted;
        if (exact) {
          try {
            predicted = exact->state_at(p.t_s);
          } catch (const std::exception& e) {
            // The closed form from this segment's start cannot reach t (a start state so
            // large that the parabola overflows): this segment has no prediction, and only
            // this one. Figures already computed for it are dropped with it.
            exact.reset();
            seg.predicted = false;
            seg.note = "no prediction: the closed form from " + start_text(seg.plan) +
                       " fails at t = " + format_value(p.t_s) + " s: " + e.what();
            for (PhysicsSample& earlier : result.samples) {
              if (earlier.segment == p.segment) earlier.orientation_error = nan;
              if (earlier.segment == p.segment) earlier.position_error = nan;
            }
            seg.max_orientation_error = seg.max_position_error = 0.0;
          }
        }
        if (predicted) {
          p.orientation_error = orientation_error(predicted->orientation, s.orientation);
          p.position_error = (predicted->position_world - s.position_world).norm();
        } else {
          p.orientation_error = p.position_error = nan;
        }
      }
      // fmax: a sample without a figure (NaN) does not hide the others. Such a sample still
      // fails --strict: a zero quaternion through | |q| - 1 | = 1, a non-finite value through
      // the count in non_finite_odom.
      seg.duration_s = std::max(seg.duration_s, p.t_s);
      seg.max_angular_speed_radps = std::fmax(seg.max_angular_speed_radps, p.angular_speed_radps);
      seg.max_abs_position = std::fmax(seg.max_abs_position, o.position_world.norm());
      seg.max_quat_norm_error = std::fmax(seg.max_quat_norm_error, p.quat_norm_error);
      seg.max_energy_drift = std::fmax(seg.max_energy_drift, p.energy_drift);
      seg.max_momentum_drift = std::fmax(seg.max_momentum_drift, p.momentum_drift);
      seg.max_orientation_error = std::fmax(seg.max_orientation_error, p.orientation_error);
      seg.max_position_error = std::fmax(seg.max_position_error, p.position_error);
      result.samples.push_back(p);
    }
    // A start state whose energy overflows (as huge as the one above) gives no energy drift:
    // say so rather than let every NaN drift read as the 0 that the maxima start from.
    if (start && !(std::isfinite(e0) && std::isfinite(scale))) {
      seg.max_energy_drift = nan;
      for (PhysicsSample& p : result.samples) {
        if (p.segment == result.segments.size()) p.energy_drift = nan;
      }
      if (seg.note.empty()) seg.note = "the energy of " + start_text(seg.plan) + " overflows";
    }
    if (start) {
      seg.max_angular_speed_radps = std::max(
          seg.max_angular_speed_radps,
          model.angular_velocity_world(start->orientation, start->angular_momentum_world).norm());
    }
    if (!std::isfinite(seg.min_gap_m)) seg.min_gap_m = nan;
    if (!board_note.empty() && seg.note.empty()) seg.note = board_note;
    result.segments.push_back(seg);
  }
  return result;
}

std::vector<SegmentEvent> events_of_stone(const std::vector<SegmentEvent>& events,
                                          const std::string& name, const RecordingInfo& info) {
  std::vector<SegmentEvent> own;
  for (const SegmentEvent& e : events) {
    if (e.stone == name || (e.stone.empty() && name == info.stone_frame)) own.push_back(e);
  }
  return own;
}

double energy_scale(const RigidBody& body, const Eigen::Vector3d& gravity_world) {
  return body.kinetic_energy() + std::abs(body.potential_energy(gravity_world));
}

RecordingInfo info_of_stone(const RecordingInfo& info, const StoneTrack& track) {
  const MassProperties mass =
      MassProperties::of_lens_with_mass(LensShape(track.width_m, track.height_m), track.mass_kg);
  RecordingInfo out = info;
  out.stone_frame = track.name;
  out.width_m = track.width_m;
  out.height_m = track.height_m;
  out.mass = mass.mass();
  out.principal_moments_body = mass.principal_moments_body();
  return out;
}

}  // namespace bag
}  // namespace virtual_go
