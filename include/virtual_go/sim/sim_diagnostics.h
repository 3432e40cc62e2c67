// What the node reports on /diagnostics, without ROS: the cost and pace of the updates over a
// period (UpdateStats, fed with wall times the caller measures) and one status built from them
// and the simulation's state (diagnostic_report). The node only copies the report into a
// diagnostic_msgs status.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

// The updates of one period (wall time, from the previous take() or the construction).
struct UpdateSummary {
  double period_s = 0.0;          // wall time covered
  std::int64_t updates = 0;       // updates recorded in it
  std::int64_t events = 0;        // segment events they returned
  double events_per_s = 0.0;      // events / period_s (0 for an empty period)
  double step_cost_mean_s = 0.0;  // wall time of one update: mean and largest (0: none)
  double step_cost_max_s = 0.0;
  // Simulated time advanced / wall time (0 for an empty period). Time jumps count as advanced.
  double real_time_factor = 0.0;
  // Of the latest update recorded (also from an earlier period): the steps it left for the next
  // and how far simulated time then trailed ROS time (UpdateResult).
  std::int64_t steps_deferred = 0;
  double behind_s = 0.0;
};

class UpdateStats {
 public:
  // wall_ns: any monotonic clock, the same in every call.
  explicit UpdateStats(std::int64_t wall_ns) : period_start_wall_ns_(wall_ns) {}
  // One update that took cost_wall_ns and left simulated time at sim_time_ns (0: not started).
  void record(std::int64_t cost_wall_ns, const UpdateResult& result, std::int64_t sim_time_ns);
  // The period ending at wall_ns; a new one starts there.
  UpdateSummary take(std::int64_t wall_ns);

 private:
  std::int64_t period_start_wall_ns_;
  std::int64_t period_start_sim_ns_ = 0;  // 0: the simulation had not started
  std::int64_t last_sim_ns_ = 0;
  std::int64_t updates_ = 0;
  std::int64_t events_ = 0;
  std::int64_t cost_sum_ns_ = 0;
  std::int64_t cost_max_ns_ = 0;
  std::int64_t steps_deferred_ = 0;
  std::int64_t behind_ns_ = 0;
};

// diagnostic_msgs' levels.
enum class DiagnosticLevel : std::uint8_t { ok = 0, warn = 1, error = 2 };

struct DiagnosticReport {
  DiagnosticLevel level = DiagnosticLevel::ok;
  std::string message;
  std::vector<std::pair<std::string, std::string>> values;  // key, value (units in the key)
};

// ERROR while the state is held (the message: the failure), else WARN while the last update
// left steps for the next (the physics falls behind ROS time), else OK (the message says
// "paused" while paused).
DiagnosticReport diagnostic_report(const StoneSimulation& sim, const UpdateSummary& summary);

}  // namespace virtual_go
