// Closed-form motion: translation under constant gravity, rotation for constant_omega and for
// the torque-free axisymmetric rigid body (DESIGN.md "Exact torque-free motion").
#pragma once

#include <Eigen/Geometry>

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class ExactMotion {
 public:
  // Throws InvalidArgument when the rigid_body model's inertia is not axisymmetric.
  ExactMotion(const MotionSetup& setup, const RigidBodyState& initial);

  // The state at time t (s) after the initial state, evaluated directly (no accumulation).
  // Throws InvalidArgument for a non-finite t or one so large that the state overflows.
  RigidBodyState state_at(double t) const;

  // Rotation over h as two fixed quaternions: q(t + h) = left(h) * q(t) * right(h).
  Eigen::Quaterniond left_rotation(double h) const;
  Eigen::Quaterniond right_rotation(double h) const;
  const RigidBodyState& initial() const { return initial_; }

 private:
  MotionSetup setup_;
  RigidBodyState initial_;
  Eigen::Vector3d left_rate_world_;  // L / I1 (rigid_body) or omega (constant_omega), rad/s
  double body_rate_;                 // Omega = (I3 - I1) omega3 / I1, rad/s (0 for constant_omega)
};

}  // namespace virtual_go
