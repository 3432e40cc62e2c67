#include "virtual_go/contact/pair_time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_go/common/validation.h"
#include "virtual_go/contact/flight_gap_bound.h"
#include "virtual_go/contact/gap_root.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/exact_motion.h"

namespace virtual_go {

namespace {

// Gaps above this (m) fix the normal well: touching, the normal can be a whole set of
// directions (two flat rims in one plane), and then the one seen on the approach is kept.
constexpr double kResolvableGapM = 1e-12;

// How fast one stone's reach along a fixed n can change, from its uniform axis precession.
struct ReachMotion {
  double reach_now = 0.0;     // reach(b . n), m
  double reach_growth = 0.0;  // reach can grow by at most this (its largest value is a), m
  double slope = 0.0;         // exact d reach / dt now, m/s
  double rate_bound = 0.0;    // >= |d reach / dt|, m/s
  double accel_bound = 0.0;   // >= |d^2 reach / dt^2|, m/s^2

  ReachMotion(const LensGeometry& lens, const LensPose& pose, const Eigen::Vector3d& precession,
              const Eigen::Vector3d& n) {
    const Eigen::Vector3d& b = pose.axis_world;
    const double ct = b.dot(n);
    reach_now = lens.reach(ct);
    reach_growth = std::max(0.0, lens.reach(0.0) - reach_now);
    const Eigen::Vector3d axis_rate = precession.cross(b);  // b', constant length in flight
    const double axis_speed = axis_rate.norm();
    slope = lens.reach_slope(ct) * axis_rate.dot(n);
    rate_bound = lens.sphere_offset() * axis_speed;
    // |reach''| is largest on the rim next to the cap/rim switch.
    const double kappa = std::abs(lens.reach_curvature(std::nextafter(lens.cos_cap_cone(), 0.0)));
    accel_bound =
        kappa * axis_speed * axis_speed + lens.sphere_offset() * precession.norm() * axis_speed;
  }
};

void require_options(const PairTimeOfImpactOptions& options) {
  if (!(options.polish_gap_m >= 0.0) || !(options.touch_tolerance_m >= 0.0) ||
      !std::isfinite(options.polish_gap_m) || !std::isfinite(options.touch_tolerance_m) ||
      options.max_steps < 1) {
    throw InvalidArgument("options",
                          "pair time of impact options: polish_gap_m and touch_tolerance_m must "
                          "be finite and >= 0 and max_steps >= 1, got " +
                              format_value(options.polish_gap_m) + ", " +
                              format_value(options.touch_tolerance_m) + ", " +
                              std::to_string(options.max_steps));
  }
}

MotionSetup effective_setup(const StoneMotion& stone) {
  MotionSetup setup = stone.setup;
  if (stone.supported) setup.gravity_world = Eigen::Vector3d::Zero();
  return setup;
}

}  // namespace

PairTimeOfImpact pair_time_of_impact(const StoneMotion& a, const StoneMotion& b,
                                     double start_time_s, double horizon_s,
                                     const PairTimeOfImpactOptions& options) {
  require_finite("anchor time", a.anchor_time_s);
  require_finite("anchor time", b.anchor_time_s);
  require_finite("start time", start_time_s);
  require_finite("horizon", horizon_s);
  require_options(options);
  if (horizon_s < start_time_s) {
    throw InvalidArgument("horizon_s", "horizon " + format_value(horizon_s) +
                                           " s is before the start time " +
                                           format_value(start_time_s) + " s");
  }
  const MotionSetup setup_a = effective_setup(a), setup_b = effective_setup(b);
  const ExactMotion flight_a(setup_a, a.anchor), flight_b(setup_b, b.anchor);
  const Eigen::Vector3d precession_a = axis_precession_world(setup_a.model, flight_a.initial());
  const Eigen::Vector3d precession_b = axis_precession_world(setup_b.model, flight_b.initial());
  const Eigen::Vector3d relative_gravity = setup_b.gravity_world - setup_a.gravity_world;

  PairTimeOfImpact result;
  double t = start_time_s;
  bool approached = false;
  Eigen::Vector3d approach_normal = Eigen::Vector3d::UnitZ();
  for (;;) {
    const RigidBodyState sa = flight_a.state_at(t - a.anchor_time_s);
    const RigidBodyState sb = flight_b.state_at(t - b.anchor_time_s);
    const LensPose pose_a = lens_pose(sa), pose_b = lens_pose(sb);
    LensPairContact contact = lens_pair_distance(a.lens, pose_a, b.lens, pose_b);
    if (contact.gap_m >= kResolvableGapM) {
      approached = true;
      approach_normal = contact.normal_world;
    } else if (approached) {
      // At the touch every direction that separates as well is a normal: keep the approach's.
      const LensPairContact along =
          lens_pair_contact_along(a.lens, pose_a, b.lens, pose_b, approach_normal);
      if (along.gap_m >= contact.gap_m) contact = along;
    }
    const Eigen::Vector3d& n = contact.normal_world;
    const double gap = contact.gap_m;
    const double rate = n.dot(point_velocity_world(setup_b.model, sb, contact.point_b_world) -
                              point_velocity_world(setup_a.model, sa, contact.point_a_world));
    result.time_s = t;
    result.state_a = sa;
    result.state_b = sb;
    result.contact = contact;
    result.approach_speed_mps = -rate;
    if (gap <= 0.0 && rate <= 0.0) {  // touching or overlapping, and not separating
      result.hit = true;
      return result;
    }
    if (result.advancement_steps + result.polish_steps >= options.max_steps) {
      result.exhausted = true;
      return result;
    }

    // Lower parabolas of g_n(t + tau): c0 + c1 tau + c2 tau^2 / 2.
    const ReachMotion ra(a.lens, pose_a, precession_a, n), rb(b.lens, pose_b, precession_b, n);
    const double speed = n.dot(sb.velocity_world - sa.velocity_world);
    const double accel = n.dot(relative_gravity);
    const bool touching = std::abs(gap) <= options.touch_tolerance_m;
    double step;
    if (gap > 0.0) {
      step = std::max({first_gap_root(gap - ra.reach_growth - rb.reach_growth, speed, accel),
                       first_gap_root(gap, speed - ra.rate_bound - rb.rate_bound, accel),
                       first_gap_root(gap, speed - ra.slope - rb.slope,
                                      accel - ra.accel_bound - rb.accel_bound)});
    } else if (touching) {  // separating from a touch: while g_n cannot fall below its value
      step = std::max(positive_gap_stretch(speed - ra.rate_bound - rb.rate_bound, accel),
                      positive_gap_stretch(speed - ra.slope - rb.slope,
                                           accel - ra.accel_bound - rb.accel_bound));
    } else {
      step = 0.0;  // overlapping by more than the tolerance and separating: say so now
    }
    const double min_step = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t) + 1e-18;
    if (step <= min_step) {  // no representable progress: the contact is now
      result.hit = true;
      return result;
    }
    if (t + step >= horizon_s) {
      result.time_s = horizon_s;
      result.state_a = flight_a.state_at(horizon_s - a.anchor_time_s);
      result.state_b = flight_b.state_at(horizon_s - b.anchor_time_s);
      result.contact =
          lens_pair_distance(a.lens, lens_pose(result.state_a), b.lens, lens_pose(result.state_b));
      result.approach_speed_mps = -result.contact.normal_world.dot(
          point_velocity_world(setup_b.model, result.state_b, result.contact.point_b_world) -
          point_velocity_world(setup_a.model, result.state_a, result.contact.point_a_world));
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
