// StoneSimulation's time line: update() turns ROS time (or ~step's ticks while paused) into
// physics steps within the update's budget, starts, jumps or resyncs the clock, and holds the
// state when a step fails; the controls ~pause, ~unpause and ~step.
#include <exception>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

UpdateResult StoneSimulation::update(std::int64_t now_ns) noexcept {
  UnlimitedBudget unlimited;
  return update(now_ns, unlimited);
}

UpdateResult StoneSimulation::update(std::int64_t now_ns, UpdateBudget& budget) noexcept {
  UpdateResult result;
  // Whatever fails (a step, a change, an output that would not be finite) holds the state:
  // nothing leaves this function, so no input can stop the node.
  try {
    advance_to(now_ns, budget, result);
  } catch (const std::exception& e) {
    hold(e.what(), result);
  } catch (...) {
    hold("an unknown exception", result);
  }
  return result;
}

void StoneSimulation::advance_to(std::int64_t now_ns, UpdateBudget& budget, UpdateResult& result) {
  if (paused_ && clock_.started()) {
    // Only the ticks ~step queued, whatever ROS time says.
    if (steps_queued_ > 0) steps_queued_ -= take_steps(steps_queued_, budget, result);
    return;
  }
  const SimClock::Plan plan = clock_.plan(now_ns);
  if (resync_ && plan.action != SimClock::Action::start) {
    // The first update after unpause() following ROS time: the paused interval is not
    // simulated (pausing would otherwise only delay the motion), so the time line skips it.
    resync_ = false;
    if (plan.action != SimClock::Action::wait) {
      jump_to(now_ns, "unpaused", result);
      return;
    }
  }
  switch (plan.action) {
    case SimClock::Action::wait:
      return;
    case SimClock::Action::start:
      clock_.restart(now_ns);
      start_ns_ = now_ns;
      replace_state(checked_.initial_state);
      begin_segment(EventReason::start, now_ns, result);
      restart_world(now_ns, result);
      result.advanced = true;
      result.stamp_ns = clock_.time_ns();
      return;
    case SimClock::Action::jump_back:
    case SimClock::Action::jump_forward:
      // Forward after updates the budget cut short: the physics, not ROS time, is to blame.
      jump_to(now_ns,
              behind_ && plan.action == SimClock::Action::jump_forward ? "physics_behind" : "",
              result);
      return;
    case SimClock::Action::advance: {
      const std::int64_t taken = take_steps(plan.steps, budget, result);
      if (taken < plan.steps) {
        result.steps_deferred = plan.steps - taken;
        result.behind_ns = now_ns - clock_.time_ns();
      }
      behind_ = result.steps_deferred > 0;
      return;
    }
  }
}

std::int64_t StoneSimulation::take_steps(std::int64_t steps, UpdateBudget& budget,
                                         UpdateResult& result) {
  std::int64_t taken = 0;
  for (; taken < steps; ++taken) {
    // The first step is always taken (the simulation moves on however slow a step is).
    if (taken > 0 && budget.spent()) break;
    if (held_ && !replacement_due()) {
      // Nothing can move the held state; the clock keeps to ROS time so that a reset
      // takes effect at the next grid time, and nothing is published.
      clock_.step();
      continue;
    }
    try {
      if (!step(result, budget)) break;
    } catch (const std::exception& e) {
      hold(e.what(), result);
      continue;
    }
    held_ = false;
    result.advanced = true;
    result.stamp_ns = clock_.time_ns();
  }
  // What messages show of the state to publish: once per update, not at every step (the
  // integrator refuses a non-finite state at every step; the derived numbers are checked
  // here, before anything is published).
  if (result.advanced && output_stale_) {
    try {
      output_ = state_output(checked_.setup.model, state_);
      output_stale_ = false;
    } catch (const std::exception& e) {
      result.advanced = false;
      hold(e.what(), result);
    }
  }
  return taken;
}

void StoneSimulation::jump_to(std::int64_t now_ns, const std::string& detail,
                              UpdateResult& result) {
  // The state keeps going from where it was, but on the new time line: a new segment, and
  // nothing stamped on the old one is published again.
  clock_.restart(now_ns);
  // A held state is only re-timed (so a reset takes effect near ROS time): announcing or
  // publishing it would present the stale state as new.
  if (held_) return;
  if (!initial_removed_) {
    begin_segment(EventReason::time_jump, now_ns, result);
    result.events.back().detail = detail;
  }
  behind_ = false;
  restart_world(now_ns, result);
  result.advanced = true;
  result.stamp_ns = clock_.time_ns();
}

void StoneSimulation::hold(const std::string& cause, UpdateResult& result) {
  std::string failure =
      "the physics step after " + stamp_text(clock_.time_ns()) + " s failed: " + cause;
  if (!pending_.empty()) {
    failure +=
        " (" + std::to_string(pending_.size()) + " request(s) due at that step were not applied)";
    pending_.clear();
    planned_.valid = false;
  }
  held_ = true;
  failure_ = failure;
  failure_reported_ = false;
  flight_cache_.invalidate();  // it may have moved on with the step that failed
  result.error = failure;
  if (!result.advanced) result.stamp_ns = clock_.time_ns();
  // Announced on ~events too: the state stays the last one published (at the clock's time),
  // with the cause in detail. A state whose outputs are not finite is not announced.
  try {
    announce(EventReason::held, clock_.time_ns(), state_,
             state_output(checked_.setup.model, state_), result);
  } catch (const std::exception&) {
  }
}

std::string StoneSimulation::pause() {
  if (paused_) return "already paused";
  paused_ = true;
  resync_ = false;
  return "paused at " + stamp_text(clock_.time_ns()) +
         " s: no step is taken until ~step or ~unpause; requests wait for the next step";
}

std::string StoneSimulation::unpause() {
  if (!paused_) return "not paused";
  std::string answer = "unpaused at " + stamp_text(clock_.time_ns()) + " s";
  if (steps_queued_ > 0) {
    answer += "; the " + std::to_string(steps_queued_) + " tick(s) ~step queued are dropped";
  }
  paused_ = false;
  steps_queued_ = 0;
  // Following ROS time: the paused interval is skipped at the next update (see pause()).
  resync_ = !checked_.config.publish_clock && clock_.started();
  return answer;
}

std::string StoneSimulation::step(std::int64_t ticks) {
  if (ticks < 1) {
    throw InvalidArgument("ticks", "ticks: must be at least 1, got " + std::to_string(ticks));
  }
  if (ticks > kMaxStepTicks - steps_queued_) {
    throw InvalidArgument("ticks", "ticks: at most " + std::to_string(kMaxStepTicks) +
                                       " may be queued (" + std::to_string(steps_queued_) +
                                       " already are), got " + std::to_string(ticks));
  }
  if (!paused_) {
    throw RequestRefused("refused: ~step needs the simulation paused (call ~pause first)");
  }
  steps_queued_ += ticks;
  return std::to_string(ticks) + " tick(s) of " + std::to_string(checked_.dt_ns) +
         " ns queued, taken from the next update on (" + std::to_string(steps_queued_) + " queued)";
}

}  // namespace virtual_go
