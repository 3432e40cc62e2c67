// The stone node's parameters as plain values (no ROS), their checks, and the configuration
// derived from them once. Field names follow the ROS parameter names (sim/stone_parameters.h
// pairs each with its field) and say their unit and frame; every error names the parameter.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/material.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/sim/state_request.h"
#include "virtual_go/world/world_config.h"

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
// ~contact/*/friction bound of the node. A sliding lens can meet Painleve's paradox (no
// consistent contact force) above mu ~ 0.99 (docs/physics.md, "Contact materials"); the core
// takes any mu for impacts, the node stays clear of the paradox.
constexpr double kMaxNodeFriction = 0.9;
// Largest ~contact/zeno_height: above it the cut-off would remove visible bounces.
constexpr double kMaxNodeZenoHeightM = 1e-3;
// Largest ~contact/*/rolling_resistance. The rolling couple acts through the normal force; once
// its arm is comparable with the stone it presses the contact point into the plane (as friction
// does in Painleve's paradox) and the contact model breaks down: over random orientations of a
// size-33 stone that starts at an arm of 0.9 mm for mu 0.9 (4.9 mm at mu 0.5, 9.9 mm without
// friction), and at 1 m a sample's energy rose 1.5e-10 J (docs/physics.md, "Contact
// materials"). Real arms are micrometres; the demo uses 50 um.
constexpr double kMaxNodeRollingResistanceM = 5e-4;
// Largest ~contact/*/spinning_friction: far beyond a stone's size. The spinning couple acts
// about the normal, so it cannot press the contact point into the plane.
constexpr double kMaxNodeSpinningFrictionM = 1.0;

// Hard caps on the plausibility bounds below (a bound parameter beyond its cap is refused).
// They make every number the node computes finite, whatever is requested within the bounds:
// simulated time t since a segment's start is below 2^63 ns = 9.3e9 s (int64 stamps), so
//   |v(t)| <= V + G t               <= 3e8 + 1e12 * 9.3e9              < 1e22  m/s
//   |x(t)| <= D + V t + G t^2 / 2   <= 1e12 + 2.8e18 + 4.3e31          < 1e32  m
// and, with the lens's moments between those of a thin lens (I1 = m a^2 / 6, I3 = m a^2 / 3)
// and a sphere (2 m a^2 / 5; docs/physics.md, "The lens"),
//   I      <= m a^2 / 2             <= 1e12 * 500^2 / 2                < 2e17  kg m^2
//   I      >= m a^2 / 6             >= 1e-12 * (5e-10)^2 / 6           > 4e-32 kg m^2 (normal)
//   |L|    <= I |w|                 <= 2e17 * 1e9                      < 1e27  kg m^2/s
//   |w|    <= |L| / I1 <= 2 W (I3 <= 2 I1),                 |w| t  < 2e19  rad
// and energies (m v^2, m g x, w L) at most about 1e56. Every intermediate of a quaternion-vector
// product (at most 4x its input), a squared norm (< 1e64) or an energy is then far below the
// largest double (1.8e308): no overflow anywhere in the flight, its messages or a bag.
constexpr double kMaxSpeedCap = 299792458.0;    // m/s, the speed of light
constexpr double kMaxDistanceCap = 1e12;        // m
constexpr double kMaxGravityCap = 1e12;         // m/s^2, a neutron star's surface
constexpr double kMaxAngularVelocityCap = 1e9;  // rad/s
constexpr double kMinMassCap = 1e-12;           // kg
constexpr double kMaxMassCap = 1e12;            // kg
constexpr double kMinWidthCap = 1e-9;           // m
constexpr double kMaxWidthCap = 1e3;            // m
// Requests waiting for the next physics step (none comes while ROS time stands still).
constexpr std::size_t kMaxPendingRequests = 1000;
// ~real_time_factor bounds (0 = as fast as possible). Beyond 1000 a 60 Hz timer would ask for
// 17 s of simulation per tick; below 0.001 a second of simulation takes over 16 minutes.
constexpr double kMinRealTimeFactor = 0.001;
constexpr double kMaxRealTimeFactor = 1000.0;

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
  // Plausibility bounds: requests and parameters beyond them are refused (SI units).
  double max_angular_velocity = 500.0;  // rad/s, |w|
  double max_speed = 1000.0;            // m/s, |v|
  double max_distance = 1000.0;         // m, |x| from the world origin
  double max_gravity = 1000.0;          // m/s^2, |g|
  double min_mass = 1e-6;               // kg
  double max_mass = 1000.0;             // kg
  double min_width = 0.001;             // m, lens diameter
  double max_width = 1.0;               // m
  double auto_reset_period_s = 0.0;     // 0 = never
  // The board and the table (docs/physics.md, "World"); off: the stone flies in a void.
  bool board_enabled = false;
  Eigen::Vector3d board_size_m = Eigen::Vector3d(0.4242, 0.4545, 0.1515);  // x, y, thickness
  ContactMaterial board_material;  // unmeasured placeholders (contact/material.h)
  ContactMaterial table_material;
  bool stone_contact = kDefaultStoneContact;  // stones touch each other (WorldConfig)
  double zeno_height_m = 1e-6;                // rebounds lower than this end the bouncing
  double auto_reset_after_rest_s = 0.0;       // reset once resting this long; 0 = never
  std::string world_frame = "world";
  std::string stone_frame = "stone";
  // The simulation owns the time (publishes /clock) instead of following ROS time, and runs at
  // real_time_factor times wall time; 0 = as fast as possible.
  bool publish_clock = false;
  double real_time_factor = 1.0;
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
  RequestLimits limits;
  RigidBodyState initial_state;
  // With ~board/enabled: the world the stone lives in (checked, the initial state clear of the
  // board), and the rest time after which it is reset on the dt grid (0 = never).
  std::optional<WorldConfig> world;
  std::int64_t auto_reset_after_rest_ns = 0;
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
