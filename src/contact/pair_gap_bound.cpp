#include "virtual_go/contact/pair_gap_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "virtual_go/contact/gap_root.h"

namespace virtual_go {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The smallest coefficient 1 + alpha s^2 - gamma s of N that plane_cap_force_bound accepts: the
// bound is N <= .../kappa, and a coefficient near 0 (friction couple almost cancelling the
// normal force's own lever, Painleve's regime) would make it useless anyway.
constexpr double kSmallestCoefficient = 0.1;
// Lift-off must be excluded with room: the centripetal term may use at most this share of g.
constexpr double kLiftOffShare = 0.9;
// How far (rad) the tilt may grow within the bound's validity: a smaller tilt range gives a
// smaller lever for friction and for the spin's lift.
constexpr double kTiltRoom = 0.25;

// Transverse and axial moments (I1, I3) of an axisymmetric body as the model's Euler equations
// see it; nothing when the body is not axisymmetric.
std::optional<std::pair<double, double>> axisymmetric_moments(const MotionModel& model) {
  if (model.kind() == MotionModelKind::constant_omega) {
    return std::make_pair(model.isotropic_moment(), model.isotropic_moment());
  }
  const Eigen::Vector3d& m = model.mass_properties().principal_moments_body();
  if (std::abs(m.x() - m.y()) > 1e-12 * m.x()) return std::nullopt;
  return std::make_pair(m.x(), m.z());
}

}  // namespace

GapBoundMotion still_motion() {
  GapBoundMotion m;
  m.valid_for_s = kInfinity;
  return m;
}

GapBoundMotion flight_motion(const MotionModel& model, const Eigen::Vector3d& velocity_world,
                             const Eigen::Vector3d& angular_velocity_world, double valid_for_s) {
  GapBoundMotion m;
  m.velocity_world = velocity_world;
  m.angular_velocity_world = angular_velocity_world;
  m.valid_for_s = valid_for_s;
  const double w0 = angular_velocity_world.norm();
  if (model.kind() == MotionModelKind::constant_omega) {
    m.angular_speed_radps = w0;  // omega is constant
    return m;
  }
  const Eigen::Vector3d& moments = model.mass_properties().principal_moments_body();
  const double i_min = moments.minCoeff(), i_max = moments.maxCoeff();
  // 2 K_rot = omega . I omega is conserved and lies in [I_min, I_max] |omega|^2.
  const double two_k = i_max * w0 * w0;  // >= omega . I omega now
  const double w2 = std::max(w0 * w0, two_k / i_min);
  m.angular_speed_radps = std::sqrt(w2);
  // I omega' = -omega x I omega, |omega x I omega| = |omega x (I - lambda) omega| <= (I_max -
  // I_min) / 2 |omega|^2 with lambda the middle of the moments.
  m.angular_acceleration_radps2 = 0.5 * (i_max - i_min) * w2 / i_min;
  return m;
}

std::optional<PlaneCapForceBound> plane_cap_force_bound(
    const MotionModel& model, const LensGeometry& lens, const ContactMaterial& material,
    double gravity_mps2, const Eigen::Vector3d& axis_world, const Eigen::Vector3d& velocity_world,
    const Eigen::Vector3d& angular_velocity_world, double kinetic_bound_j) {
  const auto moments = axisymmetric_moments(model);
  if (!moments || !(gravity_mps2 > 0.0)) return std::nullopt;
  const double i1 = moments->first, i3 = moments->second;
  const double i_min = std::min(i1, i3), i_max = std::max(i1, i3);
  const double m = model.mass_properties().mass();
  const double a = lens.half_width(), r = lens.sphere_radius(), d = lens.sphere_offset();
  const double cos_beta = lens.cos_cap_cone();
  const double c0 = std::min(1.0, std::abs(axis_world.z()));
  if (!(c0 > cos_beta)) return std::nullopt;  // the rim touches (or is at the switch)
  // The tilt may grow by at most kTiltRoom within the bound's validity (and stays on the cap):
  // s = sin(tilt) <= s_cap, |c| >= cos(tilt_cap).
  const double beta = std::acos(cos_beta), tilt0 = std::acos(c0);
  const double tilt_cap = std::min(beta, tilt0 + kTiltRoom);
  const double s_cap = std::sin(tilt_cap);
  const double spin_ratio = std::abs(i3 - i1) / i1;
  // No lift-off: N (1 + alpha s^2 + gamma s) >= m g - m d s w^2 (1 + |I3 - I1| / I1) / 2 > 0,
  // so |omega| must stay below w_lift (with room: kLiftOffShare of g). The energy gives
  // |omega| <= w_energy for the whole phase; w_lift holds for (w_lift - w0) / alpha(w_lift)
  // (|omega'| <= alpha while |omega| <= w_lift).
  const double w0 = angular_velocity_world.norm();
  const double w_energy =
      std::sqrt(std::max(w0 * w0, 2.0 * std::max(0.0, kinetic_bound_j) / i_min));
  const double w_lift =
      std::sqrt(2.0 * kLiftOffShare * gravity_mps2 / (d * s_cap * (1.0 + spin_ratio)));
  if (!(w0 < w_lift)) return std::nullopt;
  const double w = std::min(w_energy, w_lift);
  const double w2 = w * w;
  const double mu = material.friction, lr = material.rolling_resistance_m;
  const double ls = material.spinning_friction_m;
  const double alpha = m * d * d / i1;
  const double gamma = (m * d / i1) * (mu * (r - d * std::cos(tilt_cap)) + lr);
  // min over s in [0, s_cap] of 1 + alpha s^2 - gamma s.
  const double vertex = alpha > 0.0 ? gamma / (2.0 * alpha) : kInfinity;
  const double kappa = vertex < s_cap ? 1.0 - gamma * gamma / (4.0 * alpha)
                                      : 1.0 + alpha * s_cap * s_cap - gamma * s_cap;
  if (!(kappa >= kSmallestCoefficient)) return std::nullopt;
  PlaneCapForceBound out;
  out.normal_force_n = m * (gravity_mps2 + d * w2 * (1.0 + 0.5 * s_cap * spin_ratio)) / kappa;
  const double cone = std::sqrt(1.0 + mu * mu);
  GapBoundMotion& motion = out.motion;
  motion.velocity_world = velocity_world;
  motion.angular_velocity_world = angular_velocity_world;
  motion.force_per_mass_mps2 = out.normal_force_n * cone / m;
  motion.angular_speed_radps = w;
  // |r| <= a for the contact point on a cap (|r|^2 = R^2 + d^2 - 2 R d |c| <= a^2).
  const double torque = out.normal_force_n * (a * cone + lr + ls);
  motion.angular_acceleration_radps2 = (torque + 0.5 * (i_max - i_min) * w2) / i_min;
  motion.valid_for_s = w > 0.0 ? (tilt_cap - tilt0) / w : kInfinity;
  if (w < w_energy) {
    motion.valid_for_s =
        std::min(motion.valid_for_s, (w - w0) / motion.angular_acceleration_radps2);
  }
  return out;
}

PairGapBound::PairGapBound(const LensGeometry& lens_a, const LensPose& pose_a,
                           const GapBoundMotion& motion_a, const LensGeometry& lens_b,
                           const LensPose& pose_b, const GapBoundMotion& motion_b,
                           const Eigen::Vector3d& n, const Eigen::Vector3d& relative_gravity) {
  const double ca = pose_a.axis_world.dot(n), cb = pose_b.axis_world.dot(n);
  gap_ = n.dot(pose_b.center_world - pose_a.center_world) - lens_a.reach(ca) - lens_b.reach(cb);
  const double ca_rate = n.dot(motion_a.angular_velocity_world.cross(pose_a.axis_world));
  const double cb_rate = n.dot(motion_b.angular_velocity_world.cross(pose_b.axis_world));
  rate_ = n.dot(motion_b.velocity_world - motion_a.velocity_world) -
          lens_a.reach_slope(ca) * ca_rate - lens_b.reach_slope(cb) * cb_rate;
  const auto bend = [](const LensGeometry& lens, double c, const GapBoundMotion& m) {
    const double w = m.angular_speed_radps;
    return m.force_per_mass_mps2 +
           std::abs(lens.reach_slope(c)) * (m.angular_acceleration_radps2 + w * w);
  };
  curvature_ = n.dot(relative_gravity) - bend(lens_a, ca, motion_a) - bend(lens_b, cb, motion_b);
  valid_for_ = std::min(motion_a.valid_for_s, motion_b.valid_for_s);
}

double PairGapBound::lower_bound(double tau) const {
  return gap_ + rate_ * tau + 0.5 * curvature_ * tau * tau;
}

double PairGapBound::time_to(double level_m) const {
  return std::min(valid_for_, first_gap_root(gap_ - level_m, rate_, curvature_));
}

}  // namespace virtual_go
