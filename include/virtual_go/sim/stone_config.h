// The stone node's parameters as plain values (no ROS), and their validation. Field names
// follow the ROS parameter names (~stone/width is stone.width); every error names the parameter.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

// A bad parameter; what() starts with the parameter name, e.g. "~dt: ...".
class ConfigError : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

constexpr std::int64_t kMinDtNs = 1000;  // 1 us: smaller steps cannot keep up with real time
// ~rate bounds, Hz. The timer period 1 / rate must be a valid ros::Duration (it throws beyond
// ~68 years) and not round to 0 ns (a busy loop); this range keeps it between 0.1 ms and 1000 s.
constexpr double kMinRate = 0.001;
constexpr double kMaxRate = 10000.0;

struct StoneConfig {
  double rate = 60.0;  // Hz, publish rate
  double dt = 0.001;   // s, physics step, a whole number of nanoseconds
  std::string model = "rigid_body";
  std::string integrator = "exact";
  Eigen::Vector3d gravity = kStandardGravity;  // m/s^2, world frame
  StoneSpec stone;              // ~stone/size, width, height, material, density, mass
  std::string color = "black";  // ~stone/color: black | white
  Eigen::Vector3d initial_position = Eigen::Vector3d(0.0, 0.0, 0.05);  // m, world
  Eigen::Vector4d initial_orientation =
      Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);                             // x y z w, body->world
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();          // m/s, world
  Eigen::Vector3d initial_angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world
  double max_angular_velocity = 500.0;                                 // rad/s
  double auto_reset_period = 0.0;                                      // s, 0 = never
  std::string world_frame = "world";
  std::string stone_frame = "stone";
};

// dt in seconds -> whole nanoseconds; throws ConfigError ("~dt: ...") when dt is not positive,
// below kMinDtNs, or not a whole number of nanoseconds (to a part in 1e6 of a nanosecond).
std::int64_t dt_to_ns(double dt);

// Checks every parameter except the initial state (see StoneSimulation, which needs the built
// model for that); throws ConfigError naming the first bad parameter.
void validate_config(const StoneConfig& config);

}  // namespace virtual_go
