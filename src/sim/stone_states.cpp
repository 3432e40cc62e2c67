#include "virtual_go/sim/stone_states.h"

#include "virtual_go/go/go_point.h"

namespace virtual_go {

std::vector<StoneStateEntry> stone_states(const StoneSimulation& sim) {
  const Stone& stone = sim.stone();
  StoneStateEntry e;
  e.name = sim.stone_name(0);
  e.color = sim.config().color;
  const std::optional<WorldConfig>& world = sim.world_config();
  if (world && world->board_enabled && has_go_points(world->board)) {
    e.point = nearest_go_point_name(world->board, sim.output().position_world);
  }
  e.width_m = stone.shape.width();
  e.height_m = stone.shape.height();
  e.mass_kg = stone.mass_properties.mass();
  e.output = sim.output();
  e.resting = sim.resting();
  std::vector<StoneStateEntry> entries;
  if (sim.initial_present()) entries.push_back(e);  // not after ~remove or ~clear
  // The placed stones, from the World (a World exists whenever there are some).
  for (const PlacedStone& p : sim.placed_stones()) {
    const World& w = *sim.world();
    const WorldBody& body = w.body_model(w.body_of(p.id)).body();
    StoneStateEntry s;
    s.name = p.name;
    s.color = stone_color_name(p.color);
    s.output = state_output(body.model, w.state(p.id));
    if (has_go_points(world->board)) {
      s.point = nearest_go_point_name(world->board, s.output.position_world);
    }
    s.width_m = body.shape.width();
    s.height_m = body.shape.height();
    s.mass_kg = body.model.mass_properties().mass();
    s.resting = w.is_resting(p.id);
    entries.push_back(std::move(s));
  }
  return entries;
}

bool stone_states_due(const UpdateResult& result, bool all_resting, bool listened) {
  if (!result.advanced) return false;  // no new state: nothing new to say
  return !result.events.empty() || (!all_resting && listened);
}

}  // namespace virtual_go
