// Validation of state changes requested from outside the physics (service calls and the
// initial state parameters). Each rejection throws InvalidArgument whose field() is the request
// field as the caller named it, so bad input never reaches the state.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

// What a requested (or initial) state may be: the plausibility bounds of the configuration
// (~max_distance, ~max_speed, ~max_angular_velocity) and the integrator's step limit
// (dt * |w| <= max_rotation_per_step). |w| is constant in torque-free motion of an axisymmetric
// body, so checking it once suffices.
struct RequestLimits {
  double max_distance;           // m, |x| from the world origin
  double max_speed;              // m/s, |v|
  double max_angular_velocity;   // rad/s
  double max_rotation_per_step;  // rad, the integrator's limit (may be infinity)
  double dt_s;                   // s
  std::string integrator;        // for the message
};

// Each throws InvalidArgument naming `field`, the value and the limit; the norms are taken
// without overflow, so a component near the largest double is reported as it is.
void check_position(const std::string& field, const Eigen::Vector3d& position_world,
                    const RequestLimits& limits);
void check_velocity(const std::string& field, const Eigen::Vector3d& velocity_world,
                    const RequestLimits& limits);
void check_angular_velocity(const std::string& field, const Eigen::Vector3d& omega,
                            const RequestLimits& limits);

enum class RequestFrame { world, body };

// "" or "world" or the world frame id -> world; "stone" or the stone frame id -> body. An
// unknown frame is quoted cut to a short length (quote_user_text).
RequestFrame request_frame(const std::string& field, const std::string& frame,
                           const std::string& world_frame, const std::string& stone_frame);

// Names of the fields a full state comes from, for messages ("pose.position" or
// "initial/position").
struct StateFieldNames {
  std::string position, orientation, velocity, angular_velocity;
};

// Builds a checked state (unit orientation, L from omega by the model) from world-frame values
// within `limits`; every refusal names the field of `fields`. orientation_xyzw is (x, y, z, w)
// like the ROS messages and parameters; any finite non-zero one is normalised.
RigidBodyState state_from_request(const StateFieldNames& fields, const MotionModel& model,
                                  const Eigen::Vector3d& position_world,
                                  const Eigen::Vector4d& orientation_xyzw,
                                  const Eigen::Vector3d& velocity_world,
                                  const Eigen::Vector3d& angular_velocity_world,
                                  const RequestLimits& limits);

}  // namespace virtual_go
