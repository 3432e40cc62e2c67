#include "virtual_go/world/stone_mode.h"

namespace virtual_go {

std::string stone_mode_name(StoneMode mode) {
  switch (mode) {
    case StoneMode::flight:
      return "flight";
    case StoneMode::contact:
      return "contact";
    case StoneMode::resting:
      return "resting";
  }
  return "unknown";
}

std::string contact_phase_name(ContactPhase phase) {
  switch (phase) {
    case ContactPhase::none:
      return "none";
    case ContactPhase::plane:
      return "plane";
    case ContactPhase::nonsmooth:
      return "nonsmooth";
  }
  return "unknown";
}

}  // namespace virtual_go
