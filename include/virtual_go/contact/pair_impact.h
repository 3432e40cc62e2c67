// The impact of two free stones (docs/physics.md, "Stone–stone contact (primitives)"): the
// one-body impact's law (impact.h) for two bodies. With lever arms r_A = P - x_A, r_B = P - x_B
// and the normal n from A to B, the relative contact velocity u = u_B - u_A changes by K P under
// the impulse P on B (-P on A), with K = K_A + K_B, K_i = (1/m_i) 1 - [r_i]x I_i,world^-1 [r_i]x.
// The impulse-space process (Coulomb friction integrated through the impact, ended by Stronge's
// energetic coefficient: Stronge, "Impact Mechanics", 2000; Proc. R. Soc. A 431, 1991) sees only
// K and u, so it is the one-body process unchanged, and dE = P . u- + P^T K P / 2 =
// (1 - e*^2) W_c - mu int |u_t| dp <= 0. Linear momentum is conserved exactly by construction
// (equal and opposite impulses) and so is the angular momentum about any fixed point.
//
// Both bodies are free: a stone resting on the board takes part with its full mass, the board's
// own reaction is not part of this primitive (simultaneous contacts are not resolved here).
// There is no Zeno cut-off: sustained stone-stone contact is a separate mode.
#pragma once

#include <Eigen/Core>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/material.h"

namespace virtual_go {

struct PairImpact {
  RigidBodyState state_a, state_b;  // after: v and L changed by -P and +P at the contact point
  Eigen::Vector3d impulse_world = Eigen::Vector3d::Zero();  // on B (A takes -impulse), N s
  double energy_change_j = 0.0;                             // P . u- + P^T K P / 2, <= 0
  double compression_impulse_ns = 0.0;  // normal impulse at the end of compression, N s
  double normal_impulse_ns = 0.0;       // total normal impulse, N s
  // Relative contact velocity u = u_B - u_A along n, m/s: < 0 approaching.
  double normal_velocity_before_mps = 0.0;
  double normal_velocity_after_mps = 0.0;
  Eigen::Vector3d contact_velocity_before_world = Eigen::Vector3d::Zero();  // u-, m/s
  Eigen::Vector3d contact_velocity_after_world = Eigen::Vector3d::Zero();   // u+, m/s
  bool separating = false;             // u_n- >= 0: no impulse, states unchanged
  bool stuck = false;                  // the relative slip ended (u_t = 0) and stayed so
  int slip_steps = 0;                  // accepted steps of the slip integration
  bool straight_slip = false;          // a slip was ended as a straight line (ImpactOptions)
  bool frictionless_fallback = false;  // the slip integration could not finish (ImpactOptions)
};

// Resolves the impact of stones A and B touching at contact_point_world with the unit normal
// normal_world pointing from A into B. Only options.tolerance and options.max_steps are used.
// Throws InvalidArgument naming the field ("a/velocity", "contact normal", "material/friction",
// ...) for non-finite input, a zero normal or a bad material, and never fails otherwise: the work
// is bounded by options.max_steps, and every relative contact velocity is handled, 1e-300 m/s and
// denormal components included (the process runs on u / max|u_i|).
PairImpact resolve_pair_impact(const MotionModel& model_a, const RigidBodyState& before_a,
                               const MotionModel& model_b, const RigidBodyState& before_b,
                               const Eigen::Vector3d& contact_point_world,
                               const Eigen::Vector3d& normal_world, const ContactMaterial& material,
                               const ImpactOptions& options = {});

}  // namespace virtual_go
