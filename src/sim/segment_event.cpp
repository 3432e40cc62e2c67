#include "virtual_go/sim/segment_event.h"

namespace virtual_go {

std::string event_reason_name(EventReason reason) {
  switch (reason) {
    case EventReason::start:
      return "start";
    case EventReason::reset:
      return "reset";
    case EventReason::auto_reset:
      return "auto_reset";
    case EventReason::set_state:
      return "set_state";
    case EventReason::set_angular_velocity:
      return "set_angular_velocity";
    case EventReason::time_jump:
      return "time_jump";
  }
  return "unknown";
}

}  // namespace virtual_go
