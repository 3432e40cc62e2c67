// Notices when ROS time stands still while wall time goes on: under use_sim_time the node then
// waits for /clock (none published yet, or its publisher stopped) and publishes nothing, which
// a user cannot tell from a broken node unless it says so. Fed both clocks; ROS-free.
#pragma once

#include <cstdint>

namespace virtual_go {

class ClockWatch {
 public:
  enum class Change {
    none,
    stalled,  // ROS time has not moved for `patience` of wall time: reported once per stall
    resumed,  // ROS time moved again after a reported stall
  };

  // patience_ns > 0: how long ROS time may stand still before it counts as a stall.
  explicit ClockWatch(std::int64_t patience_ns);

  // wall_ns: a monotonic wall clock; ros_ns: ROS time now (0 = no /clock received yet).
  Change observe(std::int64_t wall_ns, std::int64_t ros_ns);

  std::int64_t patience_ns() const { return patience_ns_; }

 private:
  std::int64_t patience_ns_;
  bool seen_ = false;
  bool reported_ = false;
  std::int64_t last_ros_ns_ = 0;
  std::int64_t still_since_wall_ns_ = 0;  // wall time at which ROS time last moved
};

}  // namespace virtual_go
