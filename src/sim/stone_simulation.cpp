// StoneSimulation (sim/stone_simulation.h), split by job into:
//   stone_simulation.cpp           construction and the stones' names and bodies (this file)
//   stone_simulation_requests.cpp  requests from outside: checked at once, queued for a step
//   stone_simulation_planning.cpp  the set-down planner's view of the board the queue leaves
//   stone_simulation_timeline.cpp  update(): which steps ROS time, the budget and the controls
//                                  allow, time jumps, and holding the state after a failure
//   stone_simulation_step.cpp      one physics step, with the changes due at it
//   stone_simulation_world.cpp     the World kept in step: its restarts, changes applied to it
//   stone_simulation_events.cpp    segment events: from the World's, numbered and announced
#include "virtual_go/sim/stone_simulation.h"

#include <algorithm>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {
namespace {

// 1 s behind ROS time: skip rather than catch up.
constexpr std::int64_t kMaxLagNs = kNanosecondsPerSecond;

}  // namespace

StoneSimulation::StoneSimulation(const StoneConfig& config)
    : StoneSimulation(check_config(config)) {}

StoneSimulation::StoneSimulation(CheckedConfig checked)
    : checked_(std::move(checked)),
      integrator_(checked_.integrator->make(*checked_.integrator, checked_.setup)),
      clock_(checked_.dt_ns, std::max(kMaxLagNs, 2 * checked_.dt_ns)),
      state_(checked_.initial_state),
      output_(state_output(checked_.setup.model, checked_.initial_state)) {
  // No stone until the start: a state the World refuses (tests reach states the checks refuse)
  // then holds the simulation instead of escaping from here.
  if (checked_.world) world_.emplace(*checked_.world, std::vector<RigidBodyState>{}, 0.0);
}

const std::string& StoneSimulation::stone_name(std::size_t index) const {
  // One stone today, named by its frame (~stone_frame, "stone" by default).
  if (index != 0) throw std::logic_error("stone index " + std::to_string(index) + " of 1 stone");
  return checked_.config.stone_frame;
}

std::string StoneSimulation::name_of(StoneId id) const {
  if (id == initial_id_) return stone_name(0);
  for (const PlacedStone& p : placed_) {
    if (p.id == id) return p.name;
  }
  return "";
}

const PlacedStone* StoneSimulation::placed_named(const std::string& name) const {
  const auto it = std::find_if(placed_.begin(), placed_.end(),
                               [&](const PlacedStone& p) { return p.name == name; });
  return it == placed_.end() ? nullptr : &*it;
}

const StoneSimulation::Change* StoneSimulation::place_waiting(const std::string& name) const {
  const auto it = std::find_if(pending_.begin(), pending_.end(), [&](const Change& c) {
    return c.reason == EventReason::place && c.name == name;
  });
  return it == pending_.end() ? nullptr : &*it;
}

const MotionModel& StoneSimulation::model_of(StoneId id) const {
  for (std::size_t k = 0; k < placed_.size(); ++k) {
    if (placed_[k].id == id) return world_->body_model(body_of_placed_[k]).setup().model;
  }
  return checked_.setup.model;
}

}  // namespace virtual_go
