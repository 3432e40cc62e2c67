// With ~publish_clock the node owns simulated time instead of following ROS time (it publishes
// /clock from it): SimPacer decides, at each wall-timer tick, how far the simulation goes. It
// runs at ~real_time_factor times wall time (0: as far as the update budget allows), in updates
// that each end at a sample instant of simulated time, one per ~rate period (so a bag recorded
// at factor 0 holds states at ~rate of simulated time, not of wall time). Stamps stay on the
// ~dt grid of whole nanoseconds: the pacer only picks the times the updates run to. When the
// physics cannot keep the pace within the budget, the pace restarts from where the simulation
// is (it runs slower than asked, never skips). ROS-free: the caller gives a monotonic wall time
// and publishes what each update returns.
#pragma once

#include <cstdint>
#include <functional>

#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/update_budget.h"

namespace virtual_go {

// Where simulated time starts with ~publish_clock: ROS reads time 0 as "not set" (the clock
// would not start), and a round second reads better in /clock and bags than ~dt would.
constexpr std::int64_t kOwnClockStartNs = 1000000000;

class SimPacer {
 public:
  // rate_hz, real_time_factor: as checked by check_config (factor 0 = as fast as possible).
  SimPacer(double rate_hz, double real_time_factor);

  using Publish = std::function<void(const UpdateResult&)>;
  // One wall-timer tick at wall_ns (any monotonic clock, the same at every call): updates `sim`
  // up to the pace (the first update always runs; the next ones while `budget` lasts) and calls
  // publish after each. While paused, only the ticks ~step queued are taken.
  void tick(StoneSimulation& sim, std::int64_t wall_ns, UpdateBudget& budget,
            const Publish& publish);

  // The k-th sample instant (simulated ns): kOwnClockStartNs + k / rate, rounded to a ns.
  std::int64_t sample_ns(std::int64_t k) const;

 private:
  // The first sample index whose instant lies after time_ns.
  std::int64_t next_sample_after(std::int64_t time_ns) const;
  void anchor(std::int64_t sim_ns, std::int64_t wall_ns);

  double period_ns_;
  double real_time_factor_;
  std::int64_t next_k_ = 0;
  std::int64_t anchor_sim_ns_ = 0;
  std::int64_t anchor_wall_ns_ = 0;
  bool paced_ = false;  // anchored since the start or the last pause
};

}  // namespace virtual_go
