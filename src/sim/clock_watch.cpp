#include "virtual_go/sim/clock_watch.h"

#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {

ClockWatch::ClockWatch(std::int64_t patience_ns) : patience_ns_(patience_ns) {
  if (patience_ns <= 0) {
    throw InvalidArgument("patience_ns", "clock patience must be positive, got " +
                                             std::to_string(patience_ns) + " ns");
  }
}

ClockWatch::Change ClockWatch::observe(std::int64_t wall_ns, std::int64_t ros_ns) {
  if (!seen_ || ros_ns != last_ros_ns_) {
    // The first observation starts the wait (ROS time 0 then means "no /clock yet").
    const bool moved_after_stall = seen_ && reported_;
    seen_ = true;
    reported_ = false;
    last_ros_ns_ = ros_ns;
    still_since_wall_ns_ = wall_ns;
    return moved_after_stall ? Change::resumed : Change::none;
  }
  if (!reported_ && wall_ns - still_since_wall_ns_ >= patience_ns_) {
    reported_ = true;
    return Change::stalled;
  }
  return Change::none;
}

}  // namespace virtual_go
