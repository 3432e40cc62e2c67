#include "virtual_go/world/stone_mode.h"

#include <stdexcept>

namespace virtual_go {
namespace {

constexpr int kModes = 4;
// kTransitions[from][to], the table of stone_mode.h.
constexpr bool kTransitions[kModes][kModes] = {
    // to: flight, plane_contact, nonsmooth_contact, resting
    {true, true, true, false},   // from flight
    {true, false, true, true},   // from plane_contact
    {true, true, true, true},    // from nonsmooth_contact
    {true, false, true, false},  // from resting
};

int index_of(StoneMode mode) {
  const int i = static_cast<int>(mode);
  if (i < 0 || i >= kModes) throw std::logic_error("stone mode " + std::to_string(i) + " unknown");
  return i;
}

}  // namespace

bool is_transition(StoneMode from, StoneMode to) {
  return kTransitions[index_of(from)][index_of(to)];
}

StoneMode transition(StoneMode from, StoneMode to) {
  if (!is_transition(from, to)) {
    throw std::logic_error("stone mode transition " + stone_mode_name(from) + " -> " +
                           stone_mode_name(to) + " is not in the table (world/stone_mode.h)");
  }
  return to;
}

bool in_contact(StoneMode mode) {
  return mode == StoneMode::plane_contact || mode == StoneMode::nonsmooth_contact;
}

std::string stone_mode_name(StoneMode mode) {
  switch (mode) {
    case StoneMode::flight:
      return "flight";
    case StoneMode::plane_contact:
      return "plane_contact";
    case StoneMode::nonsmooth_contact:
      return "nonsmooth_contact";
    case StoneMode::resting:
      return "resting";
  }
  return "unknown";
}

ContactPhase contact_phase(StoneMode mode) {
  switch (mode) {
    case StoneMode::plane_contact:
      return ContactPhase::plane;
    case StoneMode::nonsmooth_contact:
      return ContactPhase::nonsmooth;
    default:
      return ContactPhase::none;
  }
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
