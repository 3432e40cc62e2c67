// What happens to a stone in the world at one instant (docs/physics.md, "World"): the event's
// time on the world's time line, the stone, the exact state right after it, and its kind at two
// levels. `kind` is what the node publishes (~events reasons): the regime the stone enters.
// `detail` is the finer cause, as the contact models report it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/world/stone_id.h"

namespace virtual_go {

// Published kinds. Every change of regime is one event carrying the state at its instant, so a
// recording splits into pieces that are each predictable (a flight in closed form between two
// events).
enum class WorldEventKind {
  impact,    // an impact on the board or the table (Stronge); a sustained-contact event follows
             // at the same time when the rebound is below the Zeno height
  slide,     // sustained contact with the contact point slipping on a cap (or any edge, corner or
             // side contact: the nonsmooth fallback)
  roll,      // sustained contact on a cap with the contact point stuck: rolling, rocking,
             // spinning in place
  rim,       // sustained contact on the rim
  lift_off,  // sustained contact ends: the stone flies
  rest,      // the stone rests: velocities exactly zero, no work until woken
  wake,      // a resting stone was woken (a command replaced its state)
};

// Finer causes.
enum class WorldEventDetail {
  impact,         // impact (the state is the one after it)
  contact_start,  // a sustained contact on a plane begins (after a Zeno impact, from the
                  // fallback, or a stone placed on the plane)
  edge_contact,   // the fallback begins after a Zeno impact or a placement on an edge, corner
                  // or side face (or two contacts at once)
  left_region,    // a plane contact's point left its face (over the board's edge): fallback
  obstacle,       // a stone on the table touched the board's side: fallback
  slip_stop,
  slip_start,
  roll_stop,
  roll_start,
  spin_stop,
  spin_start,
  cap_to_rim,
  rim_to_cap,
  lift_off,    // a plane contact's normal force reached zero
  separation,  // the fallback found the stone free of every contact
  rest,        // exact rest in a plane contact
  settle,      // the fallback came to rest (by its threshold: see NonsmoothContactOptions)
  wake,
  stone_contact,  // a stone-stone contact taken by the island fallback (sustained, or a stone
                  // in contact touching another): the stone is a member of an island
  nudge,  // a resting stone moved along the top face by a placement (World::move_resting_stone):
          // kind rest, it rests at the new pose from this instant
};

struct WorldEvent {
  double time_s = 0.0;    // world time line, s
  std::size_t stone = 0;  // the stone's index when the event was handed out
  StoneId id;             // the stone's identity (stable while stones come and go)
  // The other stone of a stone-stone contact (none: the board, the table or no contact): set on
  // both stones' `impact` events of a pair impact, on the `wake` of a stone that was hit, and
  // on the `slide`/stone_contact event of a stone entering an island (the stone it touched).
  std::optional<StoneId> other;
  WorldEventKind kind = WorldEventKind::impact;
  WorldEventDetail detail = WorldEventDetail::impact;
  RigidBodyState state;  // the exact state at time_s, after the event
  // The board feature in contact (impact, contact starts) and the lens part touching it.
  bool has_feature = false;
  BoardFeature feature;
  LensPart part = LensPart::bottom_cap;
  // Impacts: the energy change (J, <= 0), the contact point's normal speed before (approach,
  // > 0) and after (rebound, >= 0), m/s.
  double energy_change_j = 0.0;
  double approach_speed_mps = 0.0;
  double rebound_speed_mps = 0.0;
};

// Names as the node publishes them: "impact", "slide", "roll", "rim", "lift_off", "rest", "wake".
std::string world_event_kind_name(WorldEventKind kind);
std::vector<std::string> world_event_kind_names();  // in the order of the enum
std::string world_event_detail_name(WorldEventDetail detail);

// The published kind of the regime a plane-contact mode is in: rim on the rim, roll when the
// contact point sticks, slide otherwise.
WorldEventKind plane_regime_kind(const PlaneContactMode& mode);
// A plane contact's event as a world event detail (none -> not an event: throws std::logic_error).
WorldEventDetail plane_event_detail(PlaneContactEvent event);

}  // namespace virtual_go
