// Validation of state changes requested from outside the physics (service calls and the
// initial state parameters). Each rejection throws InvalidArgument whose field() is the request
// field as the caller named it, so bad input never reaches the state.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

// What an angular velocity may be: under max_angular_velocity, and slow enough for the
// integrator (dt * |omega| <= its max_rotation_per_step). |omega| is constant in torque-free
// motion of an axisymmetric body, so checking it once suffices.
struct AngularVelocityLimit {
  double max_angular_velocity;   // rad/s, the ~max_angular_velocity parameter
  double max_rotation_per_step;  // rad, the integrator's limit (may be infinity)
  double dt_s;                   // s
  std::string integrator;        // for the message
};

void check_angular_velocity(const std::string& field, const Eigen::Vector3d& omega,
                            const AngularVelocityLimit& limit);

enum class RequestFrame { world, body };

// "" or "world" or the world frame id -> world; "stone" or the stone frame id -> body.
RequestFrame request_frame(const std::string& field, const std::string& frame,
                           const std::string& world_frame, const std::string& stone_frame);

// Names of the fields a full state comes from, for messages ("pose.position" or
// "initial/position").
struct StateFieldNames {
  std::string position, orientation, velocity, angular_velocity;
};

// Builds a checked state (unit orientation, L from omega by the model) from world-frame values.
// orientation_xyzw is (x, y, z, w) like the ROS messages and parameters.
RigidBodyState state_from_request(const StateFieldNames& fields, const MotionModel& model,
                                  const Eigen::Vector3d& position_world,
                                  const Eigen::Vector4d& orientation_xyzw,
                                  const Eigen::Vector3d& velocity_world,
                                  const Eigen::Vector3d& angular_velocity_world,
                                  const AngularVelocityLimit& limit);

}  // namespace virtual_go
