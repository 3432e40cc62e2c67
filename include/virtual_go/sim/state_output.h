// What the node publishes of a state, computed once and checked: the pose (/tf, ~pose), the
// twist in the stone frame (~odom) and in the world frame (~events). ROS-free.
#pragma once

#include <Eigen/Geometry>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

struct StateOutput {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();          // m
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();   // body -> world, unit
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();          // m/s
  Eigen::Vector3d angular_velocity_world = Eigen::Vector3d::Zero();  // rad/s
  Eigen::Vector3d velocity_body = Eigen::Vector3d::Zero();           // m/s, R^T v
  Eigen::Vector3d angular_velocity_body = Eigen::Vector3d::Zero();   // rad/s, R^T w
  Eigen::Vector3d angular_momentum_world = Eigen::Vector3d::Zero();  // kg m^2/s
};

// The outputs of `state` under `model`. Rotations into the stone frame are taken without
// intermediate overflow (rotate_without_overflow), so any state whose outputs are representable
// gives finite ones. Throws IntegrationError naming the first output that is not finite (or a
// quaternion that is not unit): nothing non-finite may reach a message.
StateOutput state_output(const MotionModel& model, const RigidBodyState& state);

}  // namespace virtual_go
