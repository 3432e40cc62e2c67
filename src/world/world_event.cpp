#include "virtual_go/world/world_event.h"

#include <stdexcept>
#include <utility>

namespace virtual_go {
namespace {

// Every kind once, in the order of the enum: the names the node publishes and documents.
const std::vector<std::pair<WorldEventKind, std::string>>& kinds() {
  static const std::vector<std::pair<WorldEventKind, std::string>> table{
      {WorldEventKind::impact, "impact"},     {WorldEventKind::slide, "slide"},
      {WorldEventKind::roll, "roll"},         {WorldEventKind::rim, "rim"},
      {WorldEventKind::lift_off, "lift_off"}, {WorldEventKind::rest, "rest"},
      {WorldEventKind::wake, "wake"},
  };
  return table;
}

const std::vector<std::pair<WorldEventDetail, std::string>>& details() {
  static const std::vector<std::pair<WorldEventDetail, std::string>> table{
      {WorldEventDetail::impact, "impact"},
      {WorldEventDetail::contact_start, "contact_start"},
      {WorldEventDetail::edge_contact, "edge_contact"},
      {WorldEventDetail::left_region, "left_region"},
      {WorldEventDetail::obstacle, "obstacle"},
      {WorldEventDetail::slip_stop, "slip_stop"},
      {WorldEventDetail::slip_start, "slip_start"},
      {WorldEventDetail::roll_stop, "roll_stop"},
      {WorldEventDetail::roll_start, "roll_start"},
      {WorldEventDetail::spin_stop, "spin_stop"},
      {WorldEventDetail::spin_start, "spin_start"},
      {WorldEventDetail::cap_to_rim, "cap_to_rim"},
      {WorldEventDetail::rim_to_cap, "rim_to_cap"},
      {WorldEventDetail::lift_off, "lift_off"},
      {WorldEventDetail::separation, "separation"},
      {WorldEventDetail::rest, "rest"},
      {WorldEventDetail::settle, "settle"},
      {WorldEventDetail::wake, "wake"},
      {WorldEventDetail::stone_contact, "stone_contact"},
      {WorldEventDetail::nudge, "nudge"},
  };
  return table;
}

}  // namespace

std::string world_event_kind_name(WorldEventKind kind) {
  for (const auto& [k, name] : kinds()) {
    if (k == kind) return name;
  }
  return "unknown";
}

std::vector<std::string> world_event_kind_names() {
  std::vector<std::string> names;
  for (const auto& entry : kinds()) names.push_back(entry.second);
  return names;
}

std::string world_event_detail_name(WorldEventDetail detail) {
  for (const auto& [d, name] : details()) {
    if (d == detail) return name;
  }
  return "unknown";
}

WorldEventKind plane_regime_kind(const PlaneContactMode& mode) {
  if (mode.part == LensPart::rim) return WorldEventKind::rim;
  return mode.tangential.law == ContactLaw::stuck ? WorldEventKind::roll : WorldEventKind::slide;
}

WorldEventDetail plane_event_detail(PlaneContactEvent event) {
  switch (event) {
    case PlaneContactEvent::slip_stop:
      return WorldEventDetail::slip_stop;
    case PlaneContactEvent::slip_start:
      return WorldEventDetail::slip_start;
    case PlaneContactEvent::roll_stop:
      return WorldEventDetail::roll_stop;
    case PlaneContactEvent::roll_start:
      return WorldEventDetail::roll_start;
    case PlaneContactEvent::spin_stop:
      return WorldEventDetail::spin_stop;
    case PlaneContactEvent::spin_start:
      return WorldEventDetail::spin_start;
    case PlaneContactEvent::cap_to_rim:
      return WorldEventDetail::cap_to_rim;
    case PlaneContactEvent::rim_to_cap:
      return WorldEventDetail::rim_to_cap;
    case PlaneContactEvent::lift_off:
      return WorldEventDetail::lift_off;
    case PlaneContactEvent::left_region:
      return WorldEventDetail::left_region;
    case PlaneContactEvent::obstacle:
      return WorldEventDetail::obstacle;
    case PlaneContactEvent::rest:
      return WorldEventDetail::rest;
    case PlaneContactEvent::none:
      break;
  }
  throw std::logic_error("plane_event_detail: not an event");
}

}  // namespace virtual_go
