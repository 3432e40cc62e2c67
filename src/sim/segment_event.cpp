#include "virtual_go/sim/segment_event.h"

#include <vector>

#include "virtual_go/common/name_table.h"

namespace virtual_go {
namespace {

struct ReasonEntry {
  EventReason reason;
  std::string name;
};

// Every reason once, in the order of the enum: names for messages, help, README and bag_report.
const NameTable<ReasonEntry>& reasons() {
  static const NameTable<ReasonEntry> table{
      "event reason",
      "reason",
      {
          {EventReason::start, "start"},
          {EventReason::reset, "reset"},
          {EventReason::auto_reset, "auto_reset"},
          {EventReason::set_state, "set_state"},
          {EventReason::set_angular_velocity, "set_angular_velocity"},
          {EventReason::time_jump, "time_jump"},
          {EventReason::place, "place"},
          {EventReason::remove, "remove"},
          {EventReason::clear, "clear"},
          {EventReason::impact, "impact"},
          {EventReason::slide, "slide"},
          {EventReason::roll, "roll"},
          {EventReason::rim, "rim"},
          {EventReason::lift_off, "lift_off"},
          {EventReason::rest, "rest"},
          {EventReason::wake, "wake"},
          {EventReason::held, "held"},
      }};
  return table;
}

}  // namespace

std::string event_reason_name(EventReason reason) {
  for (const ReasonEntry& e : reasons().entries()) {
    if (e.reason == reason) return e.name;
  }
  return "unknown";
}

std::vector<std::string> event_reason_names() { return reasons().names(); }

EventReason parse_event_reason(const std::string& name) { return reasons().at(name).reason; }

}  // namespace virtual_go
