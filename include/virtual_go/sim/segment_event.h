// A discontinuity in the simulated motion: the first state of a new segment. Tools that
// predict the motion from a recording restart their prediction at each one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/sim/state_output.h"

namespace virtual_go {

// From outside the physics (start ... time_jump), then, with the board, the World's changes of
// regime (world/world_event.h: impact ... wake), then held: a physics step failed and the state
// is held (detail: the cause) until a reset or set_state replaces it.
enum class EventReason {
  start,
  reset,
  auto_reset,
  set_state,
  set_angular_velocity,
  time_jump,
  impact,
  slide,
  roll,
  rim,
  lift_off,
  rest,
  wake,
  held,
};

std::string event_reason_name(EventReason reason);
// All reasons' names, in the order of the enum.
std::vector<std::string> event_reason_names();

struct SegmentEvent {
  // The segment's first instant is stamp_ns + time_offset_s: the stamp is the instant rounded
  // down to a whole ns, the offset in [0, 1e-9) s (0 for events on the dt grid). state is the
  // exact state at that instant, so a flight from a contact event is predictable exactly.
  std::int64_t stamp_ns = 0;
  double time_offset_s = 0.0;
  std::uint32_t segment = 0;  // 0 at start, +1 per event
  EventReason reason = EventReason::start;
  std::string detail;    // contact events: the World's finer cause (e.g. "slip_stop"); held: why
  RigidBodyState state;  // the segment's first state
  StateOutput output;    // what a message shows of it (checked finite)
};

}  // namespace virtual_go
