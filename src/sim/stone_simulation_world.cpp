// The World inside StoneSimulation (~board/enabled) kept in step with it: restarted on a new time
// line, and the requests due at a step applied to it stone by stone, with their events.
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

void StoneSimulation::restart_world(std::int64_t stamp_ns, UpdateResult& result) {
  if (!world_) return;
  epoch_ns_ = stamp_ns;
  rest_since_ns_ = -1;
  reset_world(state_, 0.0);
  world_events_.clear();
  mid_step_ = false;
  world_->advance_to(0.0, world_events_);
  std::vector<SegmentEvent> events;
  for (const WorldEvent& e : world_events_) events.push_back(segment_event(e));
  commit_events(events, result);
  if (initial_removed_) return;
  state_ = world_->state(initial_id_);
  output_ = state_output(checked_.setup.model, state_);
  output_stale_ = false;
}

void StoneSimulation::reset_world(const RigidBodyState& state, double t_s) {
  planned_.valid = false;
  // World::reset keeps only stones of the config's body: the placed stones are added back where
  // they are, at rest if they rested (a stone set down flat on the board rests at once).
  std::vector<RigidBodyState> placed_states;
  for (const PlacedStone& p : placed_) placed_states.push_back(world_->state(p.id));
  if (initial_removed_) {
    world_->reset({}, t_s);
  } else {
    world_->reset({state}, t_s);
    initial_id_ = world_->id(0);
  }
  // Their events at t_s (a resting stone re-added rests at once) are not reported: the stones
  // only go on, on the new time line.
  std::vector<WorldEvent> ignored;
  for (std::size_t k = 0; k < placed_.size(); ++k) {
    placed_[k].id = world_->add_stone(body_of_placed_[k], placed_states[k], t_s, ignored);
  }
}

void StoneSimulation::apply_board_changes(double t_s, std::int64_t stamp_ns, std::size_t batch_end,
                                          std::vector<SegmentEvent>& events) {
  World& world = *world_;
  const auto command = [&](EventReason reason, const std::string& name, StoneId id) {
    events.push_back(command_event(stamp_ns, reason, name, world.state(id), model_of(id)));
  };
  const auto remove_placed = [&](std::size_t k, EventReason reason) {
    command(reason, placed_[k].name, placed_[k].id);
    std::vector<WorldEvent> none;
    world.remove_stone(placed_[k].id, t_s, none);
    placed_.erase(placed_.begin() + static_cast<std::ptrdiff_t>(k));
    body_of_placed_.erase(body_of_placed_.begin() + static_cast<std::ptrdiff_t>(k));
  };
  const auto remove_initial = [&](EventReason reason) {
    if (initial_removed_) return;
    command(reason, stone_name(0), initial_id_);
    std::vector<WorldEvent> none;
    world.remove_stone(initial_id_, t_s, none);
    initial_removed_ = true;
    rest_since_ns_ = -1;
  };
  for (std::size_t n = 0; n < pending_.size(); ++n) {
    const Change& change = pending_[n];
    if (!change.on_board()) {
      // The initial stone's changes before batch_end went to the World in one (step_world).
      if (!change.initial_stone() || n >= batch_end) {
        apply_state_change(change, t_s, stamp_ns, events);
      }
      continue;
    }
    if (change.reason == EventReason::clear) {
      remove_initial(EventReason::clear);
      while (!placed_.empty()) remove_placed(0, EventReason::clear);
      continue;
    }
    if (change.reason == EventReason::remove) {
      if (change.name == stone_name(0)) {
        remove_initial(EventReason::remove);
        continue;
      }
      for (std::size_t k = 0; k < placed_.size(); ++k) {
        if (placed_[k].name == change.name) {
          remove_placed(k, EventReason::remove);
          break;
        }
      }
      continue;  // removed already (twice asked, or cleared): nothing to do
    }
    std::vector<WorldEvent> world_events;
    StoneId id;
    try {
      if (!change.point) {
        id = world.add_stone(change.color, change.state, t_s, world_events);
      } else if (change.sets_down()) {
        id = set_down_stone(world, change.color, *change.point, t_s, world_events).id;
      } else {
        id = drop_stone(world, change.color, *change.point, change.drop_height_m, t_s, world_events,
                        change.velocity_world, change.angular_velocity_world)
                 .id;
      }
    } catch (const InvalidArgument& e) {
      // Nothing was added: say so to the next caller rather than hold the simulation.
      board_note_ = change.name + " was not placed: " + e.what();
      continue;
    }
    placed_.push_back({change.name, change.color, id});
    body_of_placed_.push_back(world.body_of(id));
    command(EventReason::place, change.name, id);
    for (const WorldEvent& e : world_events) events.push_back(segment_event(e));
  }
}

void StoneSimulation::apply_state_change(const Change& change, double t_s, std::int64_t stamp_ns,
                                         std::vector<SegmentEvent>& events) {
  World& world = *world_;
  std::vector<WorldEvent> world_events;
  if (change.initial_stone() && initial_removed_) {
    // Removed earlier: only a reset brings it back (the others were refused when asked, unless
    // a reset came first).
    if (change.reason != EventReason::reset) return;
    initial_id_ = world.add_stone(0, checked_.initial_state, t_s, world_events);
    initial_removed_ = false;
    events.push_back(command_event(stamp_ns, change.reason, stone_name(0), world.state(initial_id_),
                                   model_of(initial_id_)));
    for (const WorldEvent& e : world_events) events.push_back(segment_event(e));
    return;
  }
  StoneId id = initial_id_;
  std::string name = stone_name(0);
  if (!change.initial_stone()) {
    const PlacedStone* placed = placed_named(change.name);
    if (!placed) return;  // removed by a request before it in this step
    id = placed->id;
    name = placed->name;
  }
  const MotionModel& model = model_of(id);
  RigidBodyState next = change.state;
  if (change.reason == EventReason::reset) next = checked_.initial_state;
  if (change.reason == EventReason::set_angular_velocity) {
    const RigidBodyState& now = world.state(id);
    next = with_angular_velocity_world(model, now, change.omega_world(now));
  }
  world.set_state(id, next, t_s, world_events);  // a resting stone wakes first
  append_after_wake(world_events, {command_event(stamp_ns, change.reason, name, next, model)},
                    events);
}

}  // namespace virtual_go
