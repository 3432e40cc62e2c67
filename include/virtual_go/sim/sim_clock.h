// Simulated time as whole nanoseconds on a fixed grid of dt, driven by ROS time. ROS stamps are
// whole nanoseconds, so keeping the clock in integers makes every stamp the exact time of the
// state it carries (a half-nanosecond error is already 2e-8 rad at 45 rad/s).
#pragma once

#include <cstdint>

namespace virtual_go {

class SimClock {
 public:
  enum class Action {
    wait,          // ROS time not valid yet, or not a whole step ahead: nothing to do
    start,         // first valid ROS time: the simulation starts at it
    advance,       // take `steps` steps of dt
    jump_back,     // ROS time went back before the state (a looping bag): restart at ROS time
    jump_forward,  // fell behind by more than max_lag: skip ahead to ROS time
  };
  struct Plan {
    Action action = Action::wait;
    std::int64_t steps = 0;  // advance only
  };

  // dt_ns > 0; max_lag_ns >= dt_ns: how far simulated time may trail ROS time before it skips.
  SimClock(std::int64_t dt_ns, std::int64_t max_lag_ns);

  // What to do at ROS time now_ns (0 = not valid yet, as ros::Time under use_sim_time).
  Plan plan(std::int64_t now_ns) const;
  // Starts (or restarts after a jump) the grid at now_ns.
  void restart(std::int64_t now_ns);
  // One step of dt taken.
  void step() { time_ns_ += dt_ns_; }

  bool started() const { return started_; }
  std::int64_t time_ns() const { return time_ns_; }  // simulated time of the current state
  std::int64_t next_time_ns() const { return time_ns_ + dt_ns_; }
  std::int64_t dt_ns() const { return dt_ns_; }
  std::int64_t max_lag_ns() const { return max_lag_ns_; }

 private:
  std::int64_t dt_ns_;
  std::int64_t max_lag_ns_;
  bool started_ = false;
  std::int64_t time_ns_ = 0;
};

}  // namespace virtual_go
