// A discontinuity in the simulated motion: the first state of a new segment. Tools that
// predict the motion from a recording restart their prediction at each one.
//
// The one event type outside the core: the simulation makes it from the World's events
// (world/world_event.h) and its own commands, the node copies it into virtual_go/StoneEvent
// (ros/stone_messages.h), and bag_report reads the message back into it (bag/bag_reader.h). Each
// boundary has one mapping; reasons cross every boundary as the names of one table
// (event_reason_names) and come back through parse_event_reason.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/sim/state_output.h"

namespace virtual_go {

// From outside the physics (start ... clear), then, with the board, the World's changes of
// regime (world/world_event.h: impact ... wake), then held: a physics step failed and the state
// is held (detail: the cause) until a reset or set_state replaces it.
enum class EventReason {
  start,
  reset,
  auto_reset,
  set_state,
  set_angular_velocity,
  time_jump,
  place,   // ~place: a stone added (its first state)
  remove,  // ~remove: the stone taken away (its last state)
  clear,   // ~clear: one per stone taken away
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
// The reason of a name from event_reason_names(); anything else throws InvalidArgument (field
// "reason") "unknown event reason '<name>' (known: start reset ...)".
EventReason parse_event_reason(const std::string& name);

struct SegmentEvent {
  // The segment's first instant is stamp_ns + time_offset_s: the stamp is the instant rounded
  // down to a whole ns, the offset in [0, 1e-9) s (0 for events on the dt grid). state is the
  // exact state at that instant, so a flight from a contact event is predictable exactly.
  std::int64_t stamp_ns = 0;
  double time_offset_s = 0.0;
  std::uint32_t segment = 0;  // 0 at start, +1 per event
  EventReason reason = EventReason::start;
  std::string detail;  // contact events: the World's finer cause (e.g. "slip_stop"); held: why
  // The stone's name (also its tf frame) and, for a stone-stone contact, the other stone's;
  // else empty. Read from a bag recorded before stones had names, stone is empty: the single
  // stone of ~info.
  std::string stone;
  std::string other_stone;
  RigidBodyState state;  // the segment's first state
  // What a message shows of it (checked finite). Made by the simulation only: read back from a
  // bag, state holds what the message carried, unchecked, and output stays default.
  StateOutput output;
};

}  // namespace virtual_go
