// Primary state of a rigid body; derived quantities are computed by RigidBody (rigid_body.h).
#pragma once

#include <Eigen/Geometry>

namespace virtual_go {

struct RigidBodyState {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();          // m, centre of mass
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();   // body -> world, unit
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();          // m/s
  Eigen::Vector3d angular_momentum_world = Eigen::Vector3d::Zero();  // kg m^2/s, primary

  // Throws InvalidArgument naming the field for non-finite values or a zero quaternion;
  // returns a copy with the orientation normalised.
  RigidBodyState validated() const;
  bool operator==(const RigidBodyState& other) const;  // bitwise-equal components
};

}  // namespace virtual_go
