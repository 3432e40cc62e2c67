// A stone's impact on a static obstacle (board, table): Coulomb friction integrated through the
// impact in impulse space, ended by Stronge's energetic coefficient of restitution, so no impact
// can add energy (docs/physics.md, "Impact"; Keller, J. Appl. Mech. 53, 1986; Stronge, Proc. R.
// Soc. A 431, 1991 and "Impact Mechanics", 2000; Bhatt & Koechling, J. Appl. Mech. 62, 1995).
//
// With the lever arm r = P - x_G, the impulse P on the stone changes the contact point's
// velocity by K P, K = (1/m) 1 - [r]x I_world^-1 [r]x. With the normal impulse p as the
// independent variable, du/dp = K (n + f) where the tangential part f is
//   slip:  -mu u_t / |u_t|;
//   stick (u_t = 0, |K_tt^-1 K_tn| <= mu): -K_tt^-1 K_tn, which keeps u_t = 0;
//   re-slip (u_t = 0, |K_tt^-1 K_tn| > mu): -mu s along the unique s with K_tn - mu K_tt s = l s,
//   l > 0 (a straight ray in u_t).
// Compression ends at u_n = 0 with normal work W_c = int u_n dp < 0; restitution ends when
// W = (1 - e*^2) W_c. Then dE = (1 - e*^2) W_c - mu int |u_t| dp <= 0. Slip with a curving
// direction is integrated numerically (Boost.Odeint, Runge-Kutta-Fehlberg 7(8)); stick, re-slip
// and frictionless phases are closed form; the solution steps onto u_t = 0 rather than through
// it. Newton's restitution law solved together with Coulomb friction (what LCP time-steppers
// do) can add energy to an eccentric impact; this law cannot.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/material.h"

namespace virtual_go {

struct ImpactOptions {
  // Zeno cut-off (m): when the rebound would lift the contact point less than this under
  // gravity, u_n+^2 / (2 g_n) < h_min, the restitution phase is skipped (u_n+ = 0) and the
  // contact becomes sustained. Removes at most m g h_min of energy.
  double zeno_height_m = 1e-6;
  // Relative tolerance of the slip integration (per unit of the approach speed).
  double tolerance = 1e-12;
  // Work budget of the slip integration (accepted plus rejected steps). When it is spent, or
  // a step can no longer move the impulse, the rest of the impact is taken without friction
  // (closed form, Impact::frictionless_fallback): the normal work still ends at (1 - e*^2) W_c,
  // so the impact still cannot add energy; it only dissipates less than the law would.
  int max_steps = 100000;
  // Take a slip whose direction provably stays constant to `tolerance` as a straight line, closed
  // form (docs/physics.md, "Impact"); false integrates it always (tests compare the two).
  bool straight_slip = true;
};

struct Impact {
  RigidBodyState state;  // after: v and L changed by the impulse at the contact point
  Eigen::Vector3d impulse_world = Eigen::Vector3d::Zero();  // on the stone, N s
  double energy_change_j = 0.0;                             // P . u- + P^T K P / 2, <= 0
  double compression_impulse_ns = 0.0;      // normal impulse at the end of compression, N s
  double normal_impulse_ns = 0.0;           // total normal impulse, N s
  double normal_velocity_before_mps = 0.0;  // u_n- (< 0 approaching)
  double normal_velocity_after_mps = 0.0;   // u_n+
  Eigen::Vector3d contact_velocity_before_world = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d contact_velocity_after_world = Eigen::Vector3d::Zero();   // m/s
  bool separating = false;             // u_n- >= 0: no impulse, state unchanged
  bool stuck = false;                  // the contact point's slip ended (u_t = 0) and stayed so
  bool sustained = false;              // Zeno cut-off applied: the contact stays (u_n+ = 0)
  int slip_steps = 0;                  // accepted steps of the slip integration
  bool straight_slip = false;          // a slip was ended as a straight line (ImpactOptions)
  bool frictionless_fallback = false;  // the slip integration could not finish (ImpactOptions)
};

// K = (1/m) 1 - [r]x I_world^-1 [r]x for the lever arm r (world, m), as the model sees the
// inertia (constant_omega: isotropic). Symmetric positive definite, 1/(kg).
Eigen::Matrix3d impulse_response_world(const MotionModel& model,
                                       const Eigen::Quaterniond& orientation,
                                       const Eigen::Vector3d& lever_arm_world);

// Resolves the impact of the stone in `before` touching a static obstacle at contact_point_world
// with the unit normal_world pointing from the obstacle into the stone. gravity_world is used
// only for the Zeno cut-off (g_n = -n . g; no cut-off when g_n <= 0). Throws InvalidArgument
// naming the field for non-finite input, a zero normal or a bad material, and never fails
// otherwise: the work is bounded by options.max_steps, and every contact velocity is handled,
// 1e-300 m/s and denormal components included (the process runs on u / max|u_i|).
Impact resolve_impact(const MotionModel& model, const RigidBodyState& before,
                      const Eigen::Vector3d& contact_point_world,
                      const Eigen::Vector3d& normal_world, const ContactMaterial& material,
                      const Eigen::Vector3d& gravity_world, const ImpactOptions& options = {});

}  // namespace virtual_go
