// Primary state of a rigid body; derived quantities are computed by RigidBody (rigid_body.h).
#pragma once

#include <Eigen/Geometry>

namespace virtual_go {

struct RigidBodyState {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();          // m, centre of mass
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();   // body -> world, unit
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();          // m/s
  Eigen::Vector3d angular_momentum_world = Eigen::Vector3d::Zero();  // kg m^2/s, primary

  // Throws InvalidArgument naming the field ("position", "orientation", "velocity", "angular
  // momentum") for non-finite values or a zero quaternion; returns a copy with the orientation
  // normalised.
  RigidBodyState validated() const;
  // Bitwise equality of the 13 numbers: "is this the very state, untouched?". Unlike a numeric
  // comparison it tells -0 from 0 and finds a NaN equal to the same NaN, so a state holding NaN
  // that was left alone compares equal to its copy.
  bool operator==(const RigidBodyState& other) const;
  bool operator!=(const RigidBodyState& other) const { return !(*this == other); }
};

}  // namespace virtual_go
