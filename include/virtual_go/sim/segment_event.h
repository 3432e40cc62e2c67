// A discontinuity in the simulated motion: the first state of a new segment. Tools that
// predict the motion from a recording restart their prediction at each one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/sim/state_output.h"

namespace virtual_go {

enum class EventReason { start, reset, auto_reset, set_state, set_angular_velocity, time_jump };

std::string event_reason_name(EventReason reason);
// All reasons' names, in the order of the enum.
std::vector<std::string> event_reason_names();

struct SegmentEvent {
  std::int64_t stamp_ns = 0;  // simulated time of the segment's first state
  std::uint32_t segment = 0;  // 0 at start, +1 per event
  EventReason reason = EventReason::start;
  RigidBodyState state;  // the segment's first state
  StateOutput output;    // what a message shows of it (checked finite)
};

}  // namespace virtual_go
