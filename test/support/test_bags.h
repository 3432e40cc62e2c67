// Writes synthetic bags of the stone node for the bag_report tests, with the rosbag C++ API.
// The motion comes from its own closed form (below), not from the core's ExactMotion, so a
// bug in the core's closed form cannot hide itself.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace virtual_go_test {

struct SyntheticRun {
  std::int64_t start_ns = 100'000'000'000;  // sim time of the first state (100 s)
  double rate = 50.0;                       // Hz, stamps every 20 ms
  double duration = 2.0;                    // s
  std::string integrator = "exact";
  std::string model = "rigid_body";
  bool with_info = true;
  bool with_events = true;
  bool with_tf = true;
  // Messages of ~odom, ~pose and tf to leave out (a gap) and to write twice (a repeat).
  std::vector<std::size_t> drop;
  std::vector<std::size_t> duplicate;
  // ~odom messages whose position x is NaN (a corrupted sample; ~pose and tf stay intact).
  std::vector<std::size_t> nan_odom;
  // A reset back to the initial state this long after the start (0 = none); the event is
  // written unless reset_without_event.
  double reset_after = 0.0;
  bool reset_without_event = false;
  std::string reset_reason = "reset";  // the reset event's reason (another: an unknown reason)
  // ~events as the StoneEvent version before stone names (md5sum 297586e2...): the same bytes
  // without the two empty names at the end.
  bool events_before_stone_names = false;
  // A set_state event this long after the start (0 = none) whose state is so large that its
  // closed form overflows within 0.2 s (position and velocity x 1.5e308). The recorded motion
  // goes on as before; with reset_after the reset starts a good segment again.
  double overflowing_event_after = 0.0;
  // Added to the recorded orientation angle about world z (rad per second of segment time).
  double orientation_drift_rate = 0.0;
};

// The stone of docs/physics.md's worked example: w 22 mm, h 9 mm, slate.
constexpr double kMass = 4.876e-3;
constexpr double kI1 = 1.1835e-7;
constexpr double kI3 = 2.0239e-7;

// Torque-free axisymmetric top plus free fall, evaluated directly at t.
struct TrueState {
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;  // body -> world
  Eigen::Vector3d velocity_world;
  Eigen::Vector3d angular_momentum_world;
  Eigen::Vector3d angular_velocity_body;
};
TrueState true_state(double t);

// Writes the run to path (overwrites). Returns the number of odom messages written.
std::size_t write_run_bag(const std::string& path, const SyntheticRun& run);
void write_empty_bag(const std::string& path);

}  // namespace virtual_go_test
