// The plastic impulse of Moreau-Jean's local Coulomb law (Acary & Brogliato, "Numerical Methods
// for Nonsmooth Dynamical Systems", 2008, the one-contact problem of the time-stepping scheme):
// the law holds on the velocity after the impulse, not along the impact as in the impulse-space
// process (impact.h). At a contact with unit normal n, approaching at u (m/s, u.n < 0), with
// compliance k (1/kg; u+ = u + k P, k symmetric positive definite: one body's or K_A + K_B of a
// pair), it is the impulse P (N s) with u+.n = 0 and either
//  - stick: u+ = 0 with |P_t| <= mu P_n, or
//  - slip: P_t = -mu P_n d and u+_t = lambda d, lambda >= 0 (friction against the final slip).
// Energy: dE = P.u + P.k P / 2 = P.u+ - P.k P / 2 = -mu P_n lambda - P.k P / 2 < 0, so it never
// adds energy. The island's sweeps (world/nonsmooth_island.h) take it for their plastic impulses:
// within a first-order scheme the law at the sub-step's end is the scheme's own, and it costs a
// 3x3 solve and a few Newton steps where the impulse-space process integrates the slip to 1e-12.
#pragma once

#include <Eigen/Core>

namespace virtual_go {

struct PlasticImpulse {
  Eigen::Vector3d impulse_world = Eigen::Vector3d::Zero();  // P, N s (zero: not approaching)
  // The slip direction was not found (Newton from each guess stepped where k_nn <= mu k_nt.d, or
  // settled on a root with the friction along the slip, or not at all; none in 20 000 random stone
  // contacts, test_coulomb_plastic_impulse): P is then the frictionless plastic impulse
  // -u_n / k_nn n, in the cone, dE = -u_n^2 / (2 k_nn) < 0, and the sweep's friction for a
  // slipping contact acts next (world/island_impulses.h).
  bool frictionless = false;
};

// P as above for u.n < 0, for any finite u from denormal to ~1e300 m/s (the law is homogeneous
// in u: it works on u / max|u_i|); zero when u does not approach (u.n >= 0) or is not finite.
PlasticImpulse coulomb_plastic_impulse(const Eigen::Vector3d& n, const Eigen::Matrix3d& k,
                                       const Eigen::Vector3d& u_mps, double mu);

}  // namespace virtual_go
