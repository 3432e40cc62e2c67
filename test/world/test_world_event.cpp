// Event names and the mapping of the plane contact's mode changes onto the published kinds.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/world/stone_mode.h"
#include "virtual_go/world/world_event.h"

namespace vg = virtual_go;

TEST(WorldEvent, PublishedKindsAreTheIssuesReasons) {
  const std::vector<std::string> expected{"impact",   "slide", "roll", "rim",
                                          "lift_off", "rest",  "wake"};
  EXPECT_EQ(vg::world_event_kind_names(), expected);
  EXPECT_EQ(vg::world_event_kind_name(vg::WorldEventKind::lift_off), "lift_off");
}

TEST(WorldEvent, EveryDetailHasItsOwnName) {
  std::set<std::string> names;
  for (int d = 0; d <= static_cast<int>(vg::WorldEventDetail::wake); ++d) {
    const std::string name = vg::world_event_detail_name(static_cast<vg::WorldEventDetail>(d));
    EXPECT_NE(name, "unknown");
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  EXPECT_EQ(vg::stone_mode_name(vg::StoneMode::resting), "resting");
  EXPECT_EQ(vg::contact_phase_name(vg::ContactPhase::nonsmooth), "nonsmooth");
}

// One state per stone and one table of transitions (world/stone_mode.h): a resting stone only
// wakes into a flight; rest is reached only from a contact; a flight never rests directly.
TEST(StoneMode, OneTableOfTransitions) {
  using M = vg::StoneMode;
  const M all[] = {M::flight, M::plane_contact, M::nonsmooth_contact, M::resting};
  std::set<std::string> names;
  for (const M m : all) EXPECT_TRUE(names.insert(vg::stone_mode_name(m)).second);
  for (const M m : all) {
    // A command wakes a resting stone into flight; a stone hitting it takes it into an island.
    EXPECT_EQ(vg::is_transition(M::resting, m), m == M::flight || m == M::nonsmooth_contact)
        << vg::stone_mode_name(m);
    EXPECT_EQ(vg::is_transition(m, M::resting), vg::in_contact(m)) << vg::stone_mode_name(m);
  }
  EXPECT_EQ(vg::transition(M::flight, M::plane_contact), M::plane_contact);
  EXPECT_THROW(vg::transition(M::resting, M::plane_contact), std::logic_error);
  EXPECT_EQ(vg::contact_phase(M::nonsmooth_contact), vg::ContactPhase::nonsmooth);
  EXPECT_EQ(vg::contact_phase(M::resting), vg::ContactPhase::none);
}

TEST(WorldEvent, PlaneModesMapOntoTheRegimeTheyStart) {
  vg::PlaneContactMode mode;
  mode.part = vg::LensPart::bottom_cap;
  mode.tangential.law = vg::ContactLaw::sliding;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::slide);  // slipping
  mode.tangential.law = vg::ContactLaw::free;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::slide);  // frictionless: slips
  mode.tangential.law = vg::ContactLaw::stuck;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::roll);  // slip -> stick
  mode.part = vg::LensPart::top_cap;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::roll);
  mode.part = vg::LensPart::rim;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::rim);  // cap -> rim
  mode.tangential.law = vg::ContactLaw::sliding;
  EXPECT_EQ(vg::plane_regime_kind(mode), vg::WorldEventKind::rim);
}

TEST(WorldEvent, EveryPlaneEventHasADetail) {
  const std::pair<vg::PlaneContactEvent, vg::WorldEventDetail> table[] = {
      {vg::PlaneContactEvent::slip_stop, vg::WorldEventDetail::slip_stop},
      {vg::PlaneContactEvent::slip_start, vg::WorldEventDetail::slip_start},
      {vg::PlaneContactEvent::roll_stop, vg::WorldEventDetail::roll_stop},
      {vg::PlaneContactEvent::roll_start, vg::WorldEventDetail::roll_start},
      {vg::PlaneContactEvent::spin_stop, vg::WorldEventDetail::spin_stop},
      {vg::PlaneContactEvent::spin_start, vg::WorldEventDetail::spin_start},
      {vg::PlaneContactEvent::cap_to_rim, vg::WorldEventDetail::cap_to_rim},
      {vg::PlaneContactEvent::rim_to_cap, vg::WorldEventDetail::rim_to_cap},
      {vg::PlaneContactEvent::lift_off, vg::WorldEventDetail::lift_off},
      {vg::PlaneContactEvent::left_region, vg::WorldEventDetail::left_region},
      {vg::PlaneContactEvent::obstacle, vg::WorldEventDetail::obstacle},
      {vg::PlaneContactEvent::rest, vg::WorldEventDetail::rest},
  };
  for (const auto& [event, detail] : table) EXPECT_EQ(vg::plane_event_detail(event), detail);
  EXPECT_THROW(vg::plane_event_detail(vg::PlaneContactEvent::none), std::logic_error);
}
