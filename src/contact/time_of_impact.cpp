#include "virtual_go/contact/time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_go/common/validation.h"
#include "virtual_go/contact/flight_gap_bound.h"
#include "virtual_go/flight/exact_motion.h"

namespace virtual_go {

Eigen::Vector3d point_velocity_world(const MotionModel& model, const RigidBodyState& state,
                                     const Eigen::Vector3d& point_world) {
  const Eigen::Vector3d omega =
      model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  return state.velocity_world + omega.cross(point_world - state.position_world);
}

namespace {

// Gaps above this (m) are resolved: far above the round-off of the gap (~1e-17 m), far below
// any motion of the touching point between it and the contact.
constexpr double kResolvableGapM = 1e-12;

// A corner touching the rim is a vertex on the lens's edge: the normal is anything in the rim's
// fan, and the direction from the corner to the nearest rim point, a difference of round-off
// size at the contact, says nothing. The right one is the limit of that direction as the gap
// closes: the rim point approaches the corner along its velocity's component in the meridian
// plane (r, b), so the normal is minus that component, kept within the rim's fan
// (|n . b| <= d/R). Unchanged when the approach has no meridian component.
void rim_corner_normal(const LensGeometry& lens, const MotionModel& model,
                       const RigidBodyState& state, LensContact& contact) {
  const Eigen::Vector3d b = state.orientation * Eigen::Vector3d::UnitZ();
  Eigen::Vector3d radial = contact.point_world - state.position_world;
  radial = (radial - radial.dot(b) * b).normalized();
  const Eigen::Vector3d u = point_velocity_world(model, state, contact.point_world);
  double along_radial = -u.dot(radial), along_axis = -u.dot(b);
  if (!(along_radial < 0.0)) return;  // not closing in from outside the rim
  const double limit = lens.cos_cap_cone();
  const double length = std::hypot(along_radial, along_axis);
  if (std::abs(along_axis) > limit * length) {  // clamp into the fan
    along_axis = std::copysign(limit, along_axis);
    along_radial = -std::sqrt(1.0 - limit * limit);
  } else {
    along_radial /= length;
    along_axis /= length;
  }
  contact.normal_world = along_radial * radial + along_axis * b;
}

}  // namespace

TimeOfImpact board_time_of_impact(const BoardDistance& board, const MotionSetup& setup,
                                  const RigidBodyState& anchor, double anchor_time_s,
                                  double start_time_s, double horizon_s,
                                  const TimeOfImpactOptions& options) {
  require_finite("anchor time", anchor_time_s);
  require_finite("start time", start_time_s);
  require_finite("horizon", horizon_s);
  if (!(options.polish_gap_m >= 0.0) || !(options.touch_tolerance_m >= 0.0) ||
      !std::isfinite(options.polish_gap_m) || !std::isfinite(options.touch_tolerance_m) ||
      options.max_steps < 1) {
    throw InvalidArgument("options",
                          "time of impact options: polish_gap_m and touch_tolerance_m must be "
                          "finite and >= 0 and max_steps >= 1, got " +
                              format_value(options.polish_gap_m) + ", " +
                              format_value(options.touch_tolerance_m) + ", " +
                              std::to_string(options.max_steps));
  }
  if (horizon_s < start_time_s) {
    throw InvalidArgument("horizon_s", "horizon " + format_value(horizon_s) +
                                           " s is before the start time " +
                                           format_value(start_time_s) + " s");
  }
  const ExactMotion flight(setup, anchor);
  const Eigen::Vector3d precession = axis_precession_world(setup.model, flight.initial());
  const Eigen::Vector3d& gravity = setup.gravity_world;
  const LensGeometry& lens = board.lens();
  static const Eigen::Vector3d kFaceNormals[5] = {
      Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
      -Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY()};

  TimeOfImpact result;
  double t = start_time_s;
  // The feature (and lens part) seen while the gap was still resolvable: at the contact all the
  // features through the touching point tie to round-off (a corner is on its edges) and a
  // corner's direction to the rim is a round-off-sized difference; the approach decides.
  bool approached = false;
  BoardFeature approach_feature;
  LensPart approach_part = LensPart::bottom_cap;
  for (;;) {
    const RigidBodyState state = flight.state_at(t - anchor_time_s);
    const LensPose pose = lens_pose(state);
    const BoardContact on_box = board.box(pose);
    const BoardContact on_table = board.table(pose);
    const BoardContact& nearest = on_table.lens.gap_m < on_box.lens.gap_m ? on_table : on_box;
    const double gap = nearest.lens.gap_m;
    const double rate = nearest.lens.normal_world.dot(
        point_velocity_world(setup.model, state, nearest.lens.point_world));
    result.time_s = t;
    result.state = state;
    result.contact = nearest;
    result.approach_speed_mps = -rate;
    auto hit_now = [&] {
      result.hit = true;
      if (approached && gap < kResolvableGapM) {
        if (nearest.feature != approach_feature) {
          // Only a tie: the approached feature touches too (else the step jumped to another).
          const BoardContact other = board.feature(pose, approach_feature);
          if (std::abs(other.lens.gap_m) >= kResolvableGapM) return result;
          result.contact = other;
        }
        if (approach_feature.kind == BoardFeatureKind::top_corner &&
            approach_part == LensPart::rim) {
          result.contact.lens.part = LensPart::rim;
          rim_corner_normal(lens, setup.model, state, result.contact.lens);
        }
      }
      return result;
    };
    if (gap >= kResolvableGapM) {
      approached = true;
      approach_feature = nearest.feature;
      approach_part = nearest.lens.part;
    }
    if (gap <= 0.0 && rate <= 0.0) {  // touching or overlapping, and not separating
      return hit_now();
    }
    if (result.advancement_steps + result.polish_steps >= options.max_steps) {
      result.exhausted = true;
      return result;
    }

    // The safe step: the box is apart while any of its axes keeps a positive gap (largest step
    // over the axes), the stone is free while both box and table are (smallest over the two).
    auto step_along = [&](const Eigen::Vector3d& n, double support) {
      const FlightGapBound bound(lens, pose, state.velocity_world, precession, gravity, n, support);
      const bool touching = std::abs(bound.gap()) <= options.touch_tolerance_m;
      return bound.safe_step(touching);
    };
    double box_step = 0.0;
    for (const Eigen::Vector3d& n : kFaceNormals) {
      box_step = std::max(box_step, step_along(n, board.box_support(n)));
    }
    const Eigen::Vector3d& n_box = on_box.lens.normal_world;
    box_step = std::max(box_step, step_along(n_box, board.box_support(n_box)));
    const double table_step = step_along(Eigen::Vector3d::UnitZ(), -board.board().thickness_m);
    const double step = std::min(box_step, table_step);

    // No representable progress: the contact is now (to the last bit of t).
    const double min_step = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t) + 1e-18;
    if (step <= min_step) {
      return hit_now();
    }
    if (t + step >= horizon_s) {
      result.time_s = horizon_s;
      result.state = flight.state_at(horizon_s - anchor_time_s);
      const LensPose end_pose = lens_pose(result.state);
      result.contact = board.nearest(end_pose);
      result.approach_speed_mps = -result.contact.lens.normal_world.dot(
          point_velocity_world(setup.model, result.state, result.contact.lens.point_world));
      return result;
    }
    if (gap > options.polish_gap_m) {
      ++result.advancement_steps;
    } else {
      ++result.polish_steps;
    }
    t += step;
  }
}

}  // namespace virtual_go
