// StoneSimulation's view of the board as the waiting requests will leave it, for the room
// check of a ~place set-down when it is asked: each waiting request planned once, not replayed
// at every ~place.
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

const std::vector<PlanStone>& StoneSimulation::planned_layout() {
  PlannedLayout& l = planned_;
  if (!l.valid || l.applied > pending_.size()) {
    // The planner's layout now; the requests waiting follow, in order.
    l.stones = plan_stones(*world_);
    l.names.assign(l.stones.size(), "");
    for (std::size_t i = 0; i < l.stones.size(); ++i) l.names[i] = name_of(l.stones[i].id);
    l.applied = 0;
    l.valid = true;
  }
  for (; l.applied < pending_.size(); ++l.applied) plan_change(pending_[l.applied]);
  return l.stones;
}

void StoneSimulation::plan_change(const Change& c) {
  std::vector<PlanStone>& stones = planned_.stones;
  std::vector<std::string>& names = planned_.names;
  const auto drop = [&](const std::string& n) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] != n) continue;
      names.erase(names.begin() + static_cast<std::ptrdiff_t>(i));
      stones.erase(stones.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  };
  const auto teleport = [&](const std::string& n, const RigidBodyState& state) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] != n) continue;
      stones[i].centre_xy = state.position_world.head<2>();
      stones[i].z_m = state.position_world.z();
      stones[i].movable = false;  // moving, or resting only after the step
    }
  };
  if (c.reason == EventReason::clear) {
    stones.clear();
    names.clear();
  } else if (c.reason == EventReason::remove) {
    drop(c.name);
  } else if (c.reason == EventReason::place && c.sets_down()) {
    try {
      apply_plan(stones, plan_set_down(*world_, world_->color_body(c.color), *c.point, stones));
      names.push_back(c.name);
    } catch (const InvalidArgument&) {
      // That one will be refused when it applies (the layout moved since it was accepted).
    }
  } else if (c.reason == EventReason::place && c.point) {
    // A drop nudges as a set-down does, and lands where it is aimed; within this step it is
    // where drop_stone lets it go, drop_height_m above a stone lying there (a set-down after it
    // meets it in the air, or not at all: layout_around's height band).
    SetDownPlan plan = plan_drop(*world_, world_->color_body(c.color), *c.point, stones);
    plan.stone.z_m += c.drop_height_m;
    apply_plan(stones, plan);
    names.push_back(c.name);
  } else if (c.reason == EventReason::place) {
    // By pose: where the pose puts it, never nudged (it rests only after the step, if at all).
    // A stone in the air is out of a set-down's way by layout_around's height band; one lying
    // on the board is in it.
    stones.push_back(
        PlanStone{StoneId{}, c.state.position_world.head<2>(), c.state.position_world.z(),
                  world_->body_model(world_->color_body(c.color)).lens().half_width(), false});
    names.push_back(c.name);
  } else if (c.reason == EventReason::set_state) {
    teleport(c.name.empty() ? stone_name(0) : c.name, c.state);
  } else if (c.reason == EventReason::reset) {
    drop(stone_name(0));
    const RigidBodyState& s = checked_.initial_state;
    stones.push_back(PlanStone{StoneId{}, s.position_world.head<2>(), s.position_world.z(),
                               world_->body_model(0).lens().half_width(), false});
    names.push_back(stone_name(0));
  } else if (c.reason == EventReason::set_angular_velocity) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == (c.name.empty() ? stone_name(0) : c.name)) stones[i].movable = false;
    }
  }
}

SetDownPlan StoneSimulation::check_room(std::size_t body, GoPoint point) {
  return plan_set_down(*world_, body, point, planned_layout());  // throws "point": no room
}

void StoneSimulation::planned_after(const SetDownPlan& plan) {
  // Only onto the layout of every request before it; else the next check_room plans it anew.
  if (!planned_.valid || planned_.applied + 1 != pending_.size()) return;
  apply_plan(planned_.stones, plan);
  planned_.names.push_back(pending_.back().name);
  ++planned_.applied;
}

}  // namespace virtual_go
