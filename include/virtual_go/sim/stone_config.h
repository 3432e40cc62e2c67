// The stone node's parameters as plain values (no ROS), their checks, and the configuration
// derived from them once. Field names follow the ROS parameter names (sim/stone_parameters.h
// pairs each with its field) and say their unit and frame; every error names the parameter.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/sim/state_request.h"

namespace virtual_go {

struct IntegratorInfo;

// A bad parameter: field() is the parameter as messages name it ("~dt", "~stone/size"), and
// what() starts with it, e.g. "~dt: ...".
class ConfigError : public InvalidArgument {
 public:
  ConfigError(std::string parameter, const std::string& message)
      : InvalidArgument(std::move(parameter), message) {}
};

constexpr std::int64_t kMinDtNs = 1000;  // 1 us: smaller steps cannot keep up with real time
// ~rate bounds. The timer period 1 / rate must be a valid ros::Duration (it throws beyond ~68
// years) and not round to 0 ns (a busy loop); this range keeps it between 0.1 ms and 1000 s.
constexpr double kMinRateHz = 0.001;
constexpr double kMaxRateHz = 10000.0;
constexpr double kMaxAutoResetPeriodS = 1e6;

// ~stone/color: the marker's colour.
const std::vector<std::string>& stone_colors();

struct StoneConfig {
  double rate_hz = 60.0;  // publish rate
  double dt_s = 0.001;    // physics step, a whole number of nanoseconds
  std::string model = "rigid_body";
  std::string integrator = "exact";
  Eigen::Vector3d gravity_world = kStandardGravity;  // m/s^2
  StoneSpec stone;              // ~stone/size, width, height, material, density, mass
  std::string color = "black";  // ~stone/color
  Eigen::Vector3d initial_position_world = Eigen::Vector3d(0.0, 0.0, 0.05);        // m
  Eigen::Vector4d initial_orientation_xyzw = Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);  // body->world
  Eigen::Vector3d initial_velocity_world = Eigen::Vector3d::Zero();                // m/s
  Eigen::Vector3d initial_angular_velocity_world = Eigen::Vector3d::Zero();        // rad/s
  double max_angular_velocity = 500.0;                                             // rad/s
  double auto_reset_period_s = 0.0;                                                // 0 = never
  std::string world_frame = "world";
  std::string stone_frame = "stone";
};

// A configuration that passed every check, with what is derived from it made here and only
// here: the stone (make_stone), the motion setup, dt in whole nanoseconds and the seconds the
// integrator sees, the auto-reset period on the same grid, and the initial state.
struct CheckedConfig {
  StoneConfig config;  // as given
  Stone stone;
  MotionSetup setup;
  const IntegratorInfo* integrator;
  std::int64_t dt_ns;
  double dt_s;                 // to_seconds(dt_ns), not config.dt_s
  std::int64_t auto_reset_ns;  // 0 = never
  AngularVelocityLimit angular_velocity_limit;
  RigidBodyState initial_state;
};

// dt in seconds -> whole nanoseconds; throws ConfigError ("~dt: ...") when dt is not positive,
// below kMinDtNs, or not a whole number of nanoseconds (to a part in 1e6 of a nanosecond).
std::int64_t dt_to_ns(double dt_s);

// Checks every parameter, the initial state included; throws ConfigError naming the first bad
// one.
CheckedConfig check_config(const StoneConfig& config);
// check_config without keeping the result.
void validate_config(const StoneConfig& config);

}  // namespace virtual_go
