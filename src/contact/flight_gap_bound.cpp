#include "virtual_go/contact/flight_gap_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_go/contact/gap_root.h"

namespace virtual_go {

Eigen::Vector3d axis_precession_world(const MotionModel& model, const RigidBodyState& state) {
  if (model.kind() == MotionModelKind::constant_omega) {
    return model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  }
  return state.angular_momentum_world / model.mass_properties().principal_moments_body().x();
}

FlightGapBound::FlightGapBound(const LensGeometry& lens, const LensPose& pose,
                               const Eigen::Vector3d& v, const Eigen::Vector3d& precession,
                               const Eigen::Vector3d& g, const Eigen::Vector3d& n,
                               double support_m) {
  const Eigen::Vector3d& b = pose.axis_world;
  const double ct = b.dot(n);
  reach_now_ = lens.reach(ct);
  gap_ = n.dot(pose.center_world) - reach_now_ - support_m;
  speed_ = n.dot(v);
  accel_ = n.dot(g);
  const double d = lens.sphere_offset(), cos_beta = lens.cos_cap_cone();
  const double spin = precession.norm();
  double center = ct, half_range = 0.0;  // c(t) = b(t) . n in [center - range, center + range]
  if (spin > 0.0) {
    const Eigen::Vector3d axis = precession / spin;
    const double n_along = n.dot(axis);
    const double n_across = std::sqrt(std::max(0.0, 1.0 - n_along * n_along));
    center = b.dot(axis) * n_along;
    half_range = b.cross(axis).norm() * n_across;
  }
  const double lo = center - half_range, hi = center + half_range;
  // reach is even and decreasing in |c|: its largest value is at the smallest |c| in range.
  const double smallest = (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::abs(lo), std::abs(hi));
  const double largest = std::max(std::abs(lo), std::abs(hi));
  reach_max_ = std::max(reach_now_, lens.reach(smallest));
  const double c_rate = half_range * spin;  // >= |c'|
  rate_bound_ = d * c_rate;
  // |reach''| is 0 on the caps and a / (1 - c^2)^(3/2) on the rim, growing with |c| up to the
  // switch at d/R; it matters only if the range reaches the rim.
  double curvature = 0.0;
  if (smallest < cos_beta) {
    const double c = std::min(largest, cos_beta);
    const double s2 = 1.0 - c * c;
    curvature = lens.half_width() / (s2 * std::sqrt(s2));
  }
  accel_bound_ = curvature * c_rate * c_rate + d * half_range * spin * spin;
  // Exact slope of the gap: d/dt reach(c) = reach'(c) c', c' = (Omega_p x b) . n.
  rate_ = speed_ - lens.reach_slope(ct) * precession.cross(b).dot(n);
}

double FlightGapBound::lower_bound(double tau) const {
  const double travel = speed_ * tau + 0.5 * accel_ * tau * tau;
  const double l0 = gap_ + (reach_now_ - reach_max_) + travel;
  const double l1 = gap_ + travel - rate_bound_ * tau;
  const double l2 = gap_ + (rate_ - speed_) * tau + travel - 0.5 * accel_bound_ * tau * tau;
  return std::max(l0, std::max(l1, l2));
}

double FlightGapBound::safe_step(bool touching) const {
  if (gap_ > 0.0) {
    return std::max({first_gap_root(gap_ + reach_now_ - reach_max_, speed_, accel_),
                     first_gap_root(gap_, speed_ - rate_bound_, accel_),
                     first_gap_root(gap_, rate_, accel_ - accel_bound_)});
  }
  if (!touching) return 0.0;
  return std::max(positive_gap_stretch(speed_ - rate_bound_, accel_),
                  positive_gap_stretch(rate_, accel_ - accel_bound_));
}

}  // namespace virtual_go
