// Closed-form motion (docs/physics.md, "Flight in closed form"): translation under constant
// gravity, rotation for constant_omega and for the torque-free axisymmetric rigid body.
#pragma once

#include <Eigen/Geometry>

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class ExactMotion {
 public:
  // Throws InvalidArgument when the rigid_body model's inertia is not axisymmetric (field
  // "inertia"), for a non-finite gravity or an invalid initial state.
  ExactMotion(const MotionSetup& setup, const RigidBodyState& initial);

  // The state t_s seconds after the initial state, evaluated directly (no accumulation).
  // Throws InvalidArgument (field "time") for a non-finite t_s or one so large that the state
  // overflows.
  RigidBodyState state_at(double t_s) const;

  // Rotation over h_s as two fixed quaternions: q(t + h) = left(h) * q(t) * right(h).
  Eigen::Quaterniond left_rotation(double h_s) const;
  Eigen::Quaterniond right_rotation(double h_s) const;
  const RigidBodyState& initial() const { return initial_; }

 private:
  Eigen::Vector3d gravity_world_;  // m/s^2
  RigidBodyState initial_;
  Eigen::Vector3d left_rate_world_;  // L / I1 (rigid_body) or omega (constant_omega), rad/s
  double body_rate_;                 // Omega = (I3 - I1) omega3 / I1, rad/s (0 for constant_omega)
};

}  // namespace virtual_go
