#include "virtual_go/sim/stone_states.h"

#include "virtual_go/go/go_point.h"

namespace virtual_go {

namespace {

// One entry, the same for the initial stone and a placed one. The point is named only where Go
// points exist: on a 19-line board that is enabled.
StoneStateEntry entry(std::string name, std::string color, const LensShape& shape, double mass_kg,
                      const StateOutput& output, bool resting,
                      const std::optional<WorldConfig>& world) {
  StoneStateEntry e;
  e.name = std::move(name);
  e.color = std::move(color);
  if (world && world->board_enabled && has_go_points(world->board)) {
    e.point = nearest_go_point_name(world->board, output.position_world);
  }
  e.width_m = shape.width();
  e.height_m = shape.height();
  e.mass_kg = mass_kg;
  e.output = output;
  e.resting = resting;
  return e;
}

}  // namespace

std::vector<StoneStateEntry> stone_states(const StoneSimulation& sim) {
  const std::optional<WorldConfig>& world = sim.world_config();
  std::vector<StoneStateEntry> entries;
  if (sim.initial_present()) {  // not after ~remove or ~clear
    const Stone& stone = sim.stone();
    entries.push_back(entry(sim.stone_name(0), sim.config().color, stone.shape,
                            stone.mass_properties.mass(), sim.output(), sim.resting(), world));
  }
  // The placed stones, from the World (a World exists whenever there are some).
  for (const PlacedStone& p : sim.placed_stones()) {
    const World& w = *sim.world();
    const WorldBody& body = w.body_model(w.body_of(p.id)).body();
    entries.push_back(entry(p.name, stone_color_name(p.color), body.shape,
                            body.model.mass_properties().mass(),
                            state_output(body.model, w.state(p.id)), w.is_resting(p.id), world));
  }
  return entries;
}

bool stone_states_due(const UpdateResult& result, bool all_resting, bool listened) {
  if (!result.advanced) return false;  // no new state: nothing new to say
  return !result.events.empty() || (!all_resting && listened);
}

}  // namespace virtual_go
