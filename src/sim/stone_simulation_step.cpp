// One physics step of StoneSimulation: the stone alone (its integrator) or the World advanced to
// the next grid time in budgeted slices, with the changes due at that step (requests, auto reset)
// applied in order.
#include <algorithm>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {
namespace {

// World work units (integrator steps, searches, impacts) between two looks at an update's budget:
// about a millisecond of hard contact (a plane-contact step costs a few microseconds).
constexpr long kWorkPerSlice = 500;

}  // namespace

bool StoneSimulation::step(UpdateResult& result, UpdateBudget& budget) {
  if (world_) return step_world(result, budget);
  const std::int64_t next_ns = clock_.next_time_ns();
  const bool auto_reset = auto_reset_due(next_ns);
  const MotionModel& model = checked_.setup.model;
  // A change that replaces the whole state (any pending one: all apply at this step) makes
  // integrating this step pointless, and lets a reset recover from a state the integrator
  // cannot handle.
  const bool replaced = replacement_due();
  // Everything below works on a copy and may throw; the simulation changes only at the end.
  RigidBodyState next = state_;
  if (!replaced) integrator_->advance(next, checked_.dt_s, flight_cache_);
  // Everything due at this step applies in order, each change announced with the state it
  // makes (segments of zero length at the same stamp, but every accepted request is seen).
  std::vector<Applied> applied = apply_changes(auto_reset, next);
  // The events carry the outputs of their states: checked before anything changes. Other
  // steps leave them to the end of update().
  for (Applied& a : applied) a.output = state_output(model, a.state);

  clock_.step();
  state_ = next;
  output_stale_ = applied.empty();
  if (!applied.empty()) output_ = applied.back().output;
  pending_.clear();
  if (!applied.empty())
    flight_cache_.invalidate();  // the integrator must not continue the old motion
  for (const Applied& a : applied) announce(a.reason, next_ns, a.state, a.output, result);
  return true;
}

// The changes due at this step (an auto reset, then the pending requests in order) applied to
// `next`; each with the state it makes (the last one's is `next`).
std::vector<StoneSimulation::Applied> StoneSimulation::apply_changes(bool auto_reset,
                                                                     RigidBodyState& next,
                                                                     std::size_t end) const {
  std::vector<Applied> applied;
  if (auto_reset) {
    next = checked_.initial_state;
    applied.push_back({EventReason::auto_reset, next, {}});
  }
  for (std::size_t k = 0; k < std::min(end, pending_.size()); ++k) {
    const Change& change = pending_[k];
    if (!change.initial_stone()) continue;  // apply_board_changes
    if (change.replaces_state()) {
      next = change.state;
    } else {
      next = with_angular_velocity_world(checked_.setup.model, next, change.omega_world(next));
    }
    applied.push_back({change.reason, next, {}});
  }
  return applied;
}

Eigen::Vector3d StoneSimulation::Change::omega_world(const RigidBodyState& now) const {
  return frame == RequestFrame::body ? rotate_without_overflow(now.orientation, omega) : omega;
}

bool StoneSimulation::step_world(UpdateResult& result, UpdateBudget& budget) {
  const std::int64_t next_ns = clock_.next_time_ns();
  const bool auto_reset = auto_reset_due(next_ns);
  World& world = *world_;
  if (!mid_step_ && !held_ && !auto_reset && pending_.empty() && world.all_resting()) {
    // At rest with nothing due: no work, the state and its outputs stay bit for bit.
    clock_.step();
    return true;
  }
  planned_.valid = false;  // the World moves on and the queue empties
  const double t_s = seconds_between(epoch_ns_, next_ns);
  const MotionModel& model = checked_.setup.model;
  // Events up to t_s (the World moves on; if anything below throws, the state is held and the
  // World restarted by the replacement that ends the hold).
  if (!mid_step_) world_events_.clear();
  if (!held_) {
    // In slices of the World's own work units, asking the update's budget between them: one
    // step of hard contact can take far longer than a tick, and the node must keep answering.
    // The first slice is always taken, so every update makes progress.
    mid_step_ = true;
    while (!world.advance_to(t_s, world_events_, WorkBudget{kWorkPerSlice}).reached) {
      if (budget.spent()) return false;
    }
    mid_step_ = false;
  }
  std::vector<SegmentEvent> events;
  for (const WorldEvent& e : world_events_) events.push_back(segment_event(e));
  // The initial stone's changes due at this step, in order, as in step(), up to its removal
  // (the rest, and all of them while it is removed, apply one by one with the board changes).
  std::size_t batch_end = 0;
  if (!initial_removed_) {
    while (batch_end < pending_.size() && !removes_initial(pending_[batch_end])) ++batch_end;
  }
  RigidBodyState next = initial_removed_ ? state_ : held_ ? state_ : world.state(initial_id_);
  const std::vector<Applied> applied =
      initial_removed_ ? std::vector<Applied>{} : apply_changes(auto_reset, next, batch_end);
  if (!applied.empty()) {
    // One event per change, each with the state it makes; the World gets the last.
    std::vector<SegmentEvent> commands;
    for (const Applied& a : applied) {
      commands.push_back(command_event(next_ns, a.reason, stone_name(0), a.state, model));
    }
    world_events_.clear();
    if (held_) {
      // The World may have failed half-way: start it afresh from the replacement.
      reset_world(next, t_s);
      world.advance_to(t_s, world_events_);
    } else {
      world.set_state(initial_id_, next, t_s, world_events_);  // a resting stone wakes first
    }
    append_after_wake(world_events_, std::move(commands), events);
  }
  apply_board_changes(t_s, next_ns, batch_end, events);
  const bool moved = !events.empty() || !world.all_resting();
  clock_.step();
  pending_.clear();
  commit_events(events, result);
  if (!initial_removed_) state_ = world.state(initial_id_);
  // Resting since before this step: the outputs already show this very state.
  if (moved) output_stale_ = true;
  return true;
}

bool StoneSimulation::auto_reset_due(std::int64_t next_ns) const {
  if (initial_removed_) return false;  // ~reset alone brings it back
  const std::int64_t auto_reset_ns = checked_.auto_reset_ns;
  if (auto_reset_ns > 0 && next_ns - segment_start_ns_ >= auto_reset_ns) return true;
  const std::int64_t after_rest_ns = checked_.auto_reset_after_rest_ns;
  return world_ && after_rest_ns > 0 && rest_since_ns_ >= 0 &&
         next_ns - rest_since_ns_ >= after_rest_ns;
}

bool StoneSimulation::replacement_due() const {
  if (auto_reset_due(clock_.next_time_ns())) return true;
  return std::any_of(pending_.begin(), pending_.end(),
                     [](const Change& change) { return change.replaces_state(); });
}

void StoneSimulation::replace_state(const RigidBodyState& state) {
  StateOutput output = state_output(checked_.setup.model, state);  // throws: nothing changed
  state_ = state;
  output_ = output;
  output_stale_ = false;
  flight_cache_.invalidate();  // the integrator must not continue the old motion
}

}  // namespace virtual_go
