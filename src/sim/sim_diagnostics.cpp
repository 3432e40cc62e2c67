#include "virtual_go/sim/sim_diagnostics.h"

#include <algorithm>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"

namespace virtual_go {

void UpdateStats::record(std::int64_t cost_wall_ns, const UpdateResult& result,
                         std::int64_t sim_time_ns) {
  ++updates_;
  events_ += static_cast<std::int64_t>(result.events.size());
  cost_sum_ns_ += cost_wall_ns;
  cost_max_ns_ = std::max(cost_max_ns_, cost_wall_ns);
  steps_deferred_ = result.steps_deferred;
  behind_ns_ = result.behind_ns;
  // Simulated time before the start is no time: the period counts from the first state.
  if (period_start_sim_ns_ == 0) period_start_sim_ns_ = sim_time_ns;
  last_sim_ns_ = sim_time_ns;
}

UpdateSummary UpdateStats::take(std::int64_t wall_ns) {
  UpdateSummary s;
  s.period_s = to_seconds(std::max<std::int64_t>(wall_ns - period_start_wall_ns_, 0));
  s.updates = updates_;
  s.events = events_;
  if (s.period_s > 0.0) {
    s.events_per_s = static_cast<double>(events_) / s.period_s;
    s.real_time_factor = to_seconds(last_sim_ns_ - period_start_sim_ns_) / s.period_s;
  }
  if (updates_ > 0) {
    s.step_cost_mean_s = to_seconds(cost_sum_ns_) / static_cast<double>(updates_);
    s.step_cost_max_s = to_seconds(cost_max_ns_);
  }
  s.steps_deferred = steps_deferred_;
  s.behind_s = to_seconds(behind_ns_);
  period_start_wall_ns_ = wall_ns;
  period_start_sim_ns_ = last_sim_ns_;
  updates_ = events_ = cost_sum_ns_ = cost_max_ns_ = 0;
  return s;
}

DiagnosticReport diagnostic_report(const StoneSimulation& sim, const UpdateSummary& summary) {
  DiagnosticReport r;
  // With the board every stone, the initial one and those ~place added, is in the World; without
  // it there is the one stone, which never rests.
  std::size_t stones = 1, resting = 0;
  if (const World* world = sim.world()) {
    stones = world->stone_count();
    for (std::size_t i = 0; i < stones; ++i) resting += world->is_resting(i) ? 1 : 0;
  }
  r.values = {
      {"stones awake", std::to_string(stones - resting)},
      {"stones resting", std::to_string(resting)},
      {"events per s", format_value(summary.events_per_s)},
      {"step cost mean (ms)", format_value(1e3 * summary.step_cost_mean_s)},
      {"step cost max (ms)", format_value(1e3 * summary.step_cost_max_s)},
      {"real-time factor", format_value(summary.real_time_factor)},
      {"pending requests", std::to_string(sim.pending_requests())},
      {"steps deferred", std::to_string(summary.steps_deferred)},
      {"behind (s)", format_value(summary.behind_s)},
      {"held", sim.held() ? "true" : "false"},
      {"paused", sim.paused() ? "true" : "false"},
      {"steps queued", std::to_string(sim.steps_queued())},
      {"period (s)", format_value(summary.period_s)},
  };
  if (sim.held()) {
    r.level = DiagnosticLevel::error;
    r.message = "held after a failed step: " + sim.failure() + "; ~reset or ~set_state replace it";
  } else if (summary.steps_deferred > 0) {
    r.level = DiagnosticLevel::warn;
    r.message = "the physics falls behind ROS time by " + format_value(summary.behind_s) + " s";
  } else if (sim.paused()) {
    r.message = "paused at " + stamp_text(sim.time_ns()) + " s (" +
                std::to_string(sim.steps_queued()) + " ~step tick(s) queued)";
  } else if (!sim.started()) {
    r.message = "waiting for a valid ROS time";
  } else {
    r.message = resting < stones ? "running"
                : stones == 1    ? "running; the stone rests"
                                 : "running; all " + std::to_string(stones) + " stones rest";
  }
  return r;
}

}  // namespace virtual_go
