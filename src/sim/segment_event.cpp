#include "virtual_go/sim/segment_event.h"

#include <utility>
#include <vector>

namespace virtual_go {
namespace {

// Every reason once, in the order of the enum: names for messages, help and README.
const std::vector<std::pair<EventReason, std::string>>& reasons() {
  static const std::vector<std::pair<EventReason, std::string>> table{
      {EventReason::start, "start"},
      {EventReason::reset, "reset"},
      {EventReason::auto_reset, "auto_reset"},
      {EventReason::set_state, "set_state"},
      {EventReason::set_angular_velocity, "set_angular_velocity"},
      {EventReason::time_jump, "time_jump"},
      {EventReason::impact, "impact"},
      {EventReason::slide, "slide"},
      {EventReason::roll, "roll"},
      {EventReason::rim, "rim"},
      {EventReason::lift_off, "lift_off"},
      {EventReason::rest, "rest"},
      {EventReason::wake, "wake"},
      {EventReason::held, "held"},
  };
  return table;
}

}  // namespace

std::string event_reason_name(EventReason reason) {
  for (const auto& [r, name] : reasons()) {
    if (r == reason) return name;
  }
  return "unknown";
}

std::vector<std::string> event_reason_names() {
  std::vector<std::string> names;
  for (const auto& entry : reasons()) names.push_back(entry.second);
  return names;
}

}  // namespace virtual_go
