#include "virtual_go/sim/stone_states.h"

#include "virtual_go/go/go_point.h"

namespace virtual_go {

std::vector<StoneStateEntry> stone_states(const StoneSimulation& sim) {
  const Stone& stone = sim.stone();
  StoneStateEntry e;
  e.name = sim.stone_name(0);
  e.color = sim.config().color;
  const std::optional<WorldConfig>& world = sim.world_config();
  // Go points are defined for the 19-line board only (go/go_point.h).
  if (world && world->board_enabled && world->board.lines == kGoLines) {
    e.point = nearest_go_point_name(world->board, sim.output().position_world);
  }
  e.width_m = stone.shape.width();
  e.height_m = stone.shape.height();
  e.mass_kg = stone.mass_properties.mass();
  e.output = sim.output();
  e.resting = sim.resting();
  return {e};
}

bool stone_states_due(const UpdateResult& result, bool all_resting, bool listened) {
  if (!result.advanced) return false;  // no new state: nothing new to say
  return !result.events.empty() || (!all_resting && listened);
}

}  // namespace virtual_go
