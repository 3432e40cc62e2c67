// Stones pushing each other: in a stone-stone contact one stone's energy may rise while its
// neighbour's falls, so the energy that must never rise is the island's total. Contact segments
// (physics_check.h) of stones whose events name each other (SegmentEvent::other_stone) are linked
// (union-find); a set of linked segments is an island, from its first link until all its
// segments end. Over that span the sum of its stones' energies (RigidBody::total_energy from
// each ~stones message, which carries the velocities) is held to the energy rise limit, and the
// per-stone energy rise of its segments counts only before the span.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/bag/physics_check.h"
#include "virtual_go/bag/recording.h"

namespace virtual_go {
namespace bag {

// One stone as the island check sees it: its model, its checked segments, its ~stones samples.
struct IslandStone {
  std::string name;
  const RecordingInfo* info = nullptr;  // info_of_stone (or ~info for the stone of ~odom)
  PhysicsResult* physics = nullptr;     // its segments (exempt_island_samples changes them)
  const StoneTrack* track = nullptr;    // its ~stones samples (the velocities)
};

struct StoneIsland {
  std::vector<std::string> members;  // stone names, sorted
  std::int64_t start_ns = 0;         // the first link (an event naming another stone)
  std::int64_t end_ns = 0;           // the last member segment's end (INT64_MAX: the recording's)
  // (stone index into the IslandStone list, segment index) of every linked contact segment.
  std::vector<std::pair<std::size_t, std::size_t>> segments;
  std::size_t snapshots = 0;  // ~stones messages in the span with every member's velocities
  // The total energy above its lowest so far in the span, relative to the largest total energy
  // scale (energy_scale summed over the members) so far; NaN when a state is unusable.
  double max_energy_rise = 0.0;
  std::int64_t worst_stamp_ns = 0;
};

struct StoneIslandResult {
  std::vector<StoneIsland> islands;  // by first link
  std::size_t worst = 0;             // index of the largest rise (NaN first); valid if any
};

StoneIslandResult check_stone_islands(const std::vector<IslandStone>& stones,
                                      const std::vector<SegmentEvent>& events,
                                      const std::vector<StonesSnapshot>& snapshots);

// A member's energy may rise while a neighbour pushes it: its segments' max_energy_rise is taken
// again over the samples before the island's span only (the samples keep their figures).
void exempt_island_samples(const StoneIslandResult& result, std::vector<IslandStone>& stones);

}  // namespace bag
}  // namespace virtual_go
