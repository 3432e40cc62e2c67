#include "virtual_go/sim/sim_clock.h"

#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {

SimClock::SimClock(std::int64_t dt_ns, std::int64_t max_lag_ns)
    : dt_ns_(dt_ns), max_lag_ns_(max_lag_ns) {
  if (dt_ns <= 0) {
    throw InvalidArgument("dt", "dt must be positive, got " + std::to_string(dt_ns) + " ns");
  }
  if (max_lag_ns < dt_ns) {
    throw InvalidArgument("max lag",
                          "max lag must be at least dt, got " + std::to_string(max_lag_ns) + " ns");
  }
}

SimClock::Plan SimClock::plan(std::int64_t now_ns) const {
  if (now_ns <= 0) return {};
  if (!started_) return {Action::start, 0};
  if (now_ns < time_ns_) return {Action::jump_back, 0};
  const std::int64_t behind_ns = now_ns - time_ns_;
  if (behind_ns > max_lag_ns_) return {Action::jump_forward, 0};
  const std::int64_t steps = behind_ns / dt_ns_;  // the remainder waits for the next tick
  if (steps == 0) return {};
  return {Action::advance, steps};
}

void SimClock::restart(std::int64_t now_ns) {
  started_ = true;
  time_ns_ = now_ns;
}

}  // namespace virtual_go
