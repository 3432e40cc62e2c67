// Guaranteed lower bounds of a flying lens's gap along one fixed direction, the step rule of
// conservative advancement (docs/physics.md, "Time of impact"; Mirtich & Canny 1995 for the
// idea). For a fixed unit direction n and a static obstacle with support h along n,
//   g_n(t) = n . x_G(t) - reach(b(t) . n) - h
// is a lower bound of the distance at every t. In exact flight n . x_G(t) is an exact parabola
// and the symmetry axis precesses uniformly about a fixed vector Omega_p (b' = Omega_p x b, the
// spin about b moves no surface point), so c(t) = b(t) . n stays in [A - B, A + B] and
// |c'| <= B |Omega_p|, |c''| <= B |Omega_p|^2 with B = |b x Omega_hat| |n x Omega_hat|. With
// |reach'| <= d and |reach''| bounded on the rim, three lower bounds follow, each a parabola:
//   L0 = n.x(t) - h - max reach over the cone               (long flights, tumbling stones)
//   L1 = g0 + (n.v - d B |Omega_p|) t + n.g t^2 / 2          (CONTACT.md's rate bound)
//   L2 = g0 + g0' t + (n.g - M) t^2 / 2                      (exact slope: Newton-like near a
//                                                             root, lets a touching stone leave)
// The safe step is the largest of their first roots: no contact along n happens before it.
#pragma once

#include <Eigen/Core>

#include "virtual_go/geometry/lens_distance.h"
#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

// The fixed vector about which the symmetry axis precesses in exact flight: L / I1 for the
// rigid body (I1 the transverse moment), omega for constant_omega. rad/s, world frame.
Eigen::Vector3d axis_precession_world(const MotionModel& model, const RigidBodyState& state);

class FlightGapBound {
 public:
  // The lens at `pose` moving with centre velocity v, axis precession Omega_p, gravity g; the
  // obstacle's support along the unit direction n is support_m.
  FlightGapBound(const LensGeometry& lens, const LensPose& pose,
                 const Eigen::Vector3d& velocity_world, const Eigen::Vector3d& precession_world,
                 const Eigen::Vector3d& gravity_world, const Eigen::Vector3d& n, double support_m);

  double gap() const { return gap_; }    // g_n(0), m
  double rate() const { return rate_; }  // dg_n/dt at 0 (exact), m/s
  // max(L0, L1, L2) at tau >= 0: never above g_n(tau).
  double lower_bound(double tau) const;
  // The first tau > 0 at which the bound reaches 0: g_n > 0 on [0, tau). +infinity if the bound
  // never does, 0 if the gap is not positive. With `touching` (the caller decided the stone
  // touches, |gap| tiny) a non-positive gap counts as 0: the step then lasts while L1 or L2,
  // started from 0, stays positive, i.e. g_n never drops below its present value; 0 if the
  // stone is not separating along n.
  double safe_step(bool touching = false) const;

 private:
  double gap_, rate_;
  double speed_, accel_;  // n . v, n . g
  double reach_now_, reach_max_;
  double rate_bound_;   // d B |Omega_p| >= |d reach / dt|
  double accel_bound_;  // >= |d^2 reach / dt^2|
};

}  // namespace virtual_go
