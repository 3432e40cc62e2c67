// A second-order lower bound of the gap between two stones over a step, for the conservative
// pass length of stones in contact (docs/physics.md, "Stone-stone contact in the world", "The
// second-order gap bound"). With the normal n of the present closest points frozen,
//   F(t) = n . (x_B - x_A) - rho_A(b_A . n) - rho_B(b_B . n)
// (lens_pair_distance.h) is a lower bound of the distance at every t, equal to it at t0. The
// reach rho is concave in its argument, so rho(c(t)) <= rho(c0) + rho'(c0) (c(t) - c0), and with
// c'' = n . (omega' x b + omega x (omega x b)):
//   F(t0 + tau) >= F0 + F'0 tau + (n . (g_B - g_A) - A) tau^2 / 2,
//   A = sum over the stones of  f + |rho'(c0)| (alpha + w^2),
// F'0 exact, f a bound of |contact force| / m, w of |omega| and alpha of |omega'| over the step.
// Gravity cancels between the two stones; only contact forces and rotation bend the bound, so a
// pair sliding side by side (F'0 ~ 0) may go a time ~ sqrt(2 F0 / A) instead of F0 / speed.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/contact/material.h"
#include "virtual_go/geometry/lens_distance.h"
#include "virtual_go/geometry/lens_geometry.h"

namespace virtual_go {

// What bounds one stone's motion over a step: its present velocities (exact) and bounds that
// hold over the whole step.
struct GapBoundMotion {
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();          // v_G now, m/s
  Eigen::Vector3d angular_velocity_world = Eigen::Vector3d::Zero();  // omega now, rad/s
  double force_per_mass_mps2 = 0.0;          // >= |contact force| / m (gravity excluded)
  double angular_speed_radps = 0.0;          // >= |omega|
  double angular_acceleration_radps2 = 0.0;  // >= |omega'|
  double valid_for_s = 0.0;  // the bounds hold on [t0, t0 + valid_for_s] (infinity: always)
};

// A stone that does not move (resting): everything zero, valid for ever.
GapBoundMotion still_motion();

// A stone in free flight (no contact force): |omega| from the rotational energy
// (w^2 <= 2 K_rot / I_min, K_rot conserved; |omega| itself for constant_omega) and
// |omega'| <= (I_max - I_min) w^2 / (2 I_min) (Euler's equations, torque-free). valid_for_s is
// the caller's: the flight's end.
GapBoundMotion flight_motion(const MotionModel& model, const Eigen::Vector3d& velocity_world,
                             const Eigen::Vector3d& angular_velocity_world, double valid_for_s);

// The bounds of a plane contact's forces over a step for a lens touching a horizontal plane
// with a cap, from the Newton-Euler equations with the contact held (plane_contact_dynamics.h)
// and every force and couple within its law (|F_t| <= mu N, |tau_r| <= l_r N, |tau_s| <= l_s N):
//   N (1 + alpha s^2 - gamma s) <= m (g + d w^2 (1 + s |I3 - I1| / (2 I1))),
//   alpha = m d^2 / I1, gamma = (m d / I1) (mu a^2 / R + l_r), s = sin(tilt) <= a / R on a cap,
// and N > 0 (no lift-off) while d w^2 (1 + s|I3 - I1| / (2 I1)) < g / 2, i.e. w < w_lift. w is
// the smaller of the energy's bound (w^2 <= 2 K / I_min, K = kinetic_bound_j, for the whole
// phase) and w_lift; the latter holds for (w_lift - |omega0|) / alpha. Valid also while the lens
// stays on its cap, for (beta - tilt0) / w with cos beta = d / R. Nothing (nullopt) when the
// bound does not apply: the rim touches, the body is not axisymmetric, |omega0| >= w_lift, or
// the coefficient is not clearly positive.
struct PlaneCapForceBound {
  double normal_force_n = 0.0;  // >= N
  GapBoundMotion motion;        // force, |omega|, |omega'| bounds and the validity time
};
std::optional<PlaneCapForceBound> plane_cap_force_bound(
    const MotionModel& model, const LensGeometry& lens, const ContactMaterial& material,
    double gravity_mps2, const Eigen::Vector3d& axis_world, const Eigen::Vector3d& velocity_world,
    const Eigen::Vector3d& angular_velocity_world, double kinetic_bound_j);

class PairGapBound {
 public:
  // Stones A and B at poses pose_a, pose_b; n the unit normal from A towards B to freeze (the
  // closest points' normal); relative_gravity = g_B - g_A (zero in one world).
  PairGapBound(const LensGeometry& lens_a, const LensPose& pose_a, const GapBoundMotion& motion_a,
               const LensGeometry& lens_b, const LensPose& pose_b, const GapBoundMotion& motion_b,
               const Eigen::Vector3d& n, const Eigen::Vector3d& relative_gravity);

  double gap() const { return gap_; }              // F(t0), m
  double rate() const { return rate_; }            // F'(t0), m/s, exact
  double curvature() const { return curvature_; }  // n . (g_B - g_A) - A, m/s^2
  double valid_for() const { return valid_for_; }  // s
  // Never above F(t0 + tau) for 0 <= tau <= valid_for().
  double lower_bound(double tau) const;
  // The first tau > 0 at which the bound falls to level_m, capped at valid_for(); 0 if the gap
  // is not above level_m.
  double time_to(double level_m) const;

 private:
  double gap_, rate_, curvature_, valid_for_;
};

}  // namespace virtual_go
