#include "virtual_go/sim/sim_pacer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace virtual_go {

SimPacer::SimPacer(double rate_hz, double real_time_factor)
    : period_ns_(1e9 / rate_hz), real_time_factor_(real_time_factor) {}

std::int64_t SimPacer::sample_ns(std::int64_t k) const {
  return kOwnClockStartNs + std::llround(static_cast<double>(k) * period_ns_);
}

std::int64_t SimPacer::next_sample_after(std::int64_t time_ns) const {
  // A first guess from the period, then exact against sample_ns's rounding.
  std::int64_t k = std::max<std::int64_t>(
      0, static_cast<std::int64_t>(
             std::floor(static_cast<double>(time_ns - kOwnClockStartNs) / period_ns_)));
  while (k > 0 && sample_ns(k - 1) > time_ns) --k;
  while (sample_ns(k) <= time_ns) ++k;
  return k;
}

void SimPacer::anchor(std::int64_t sim_ns, std::int64_t wall_ns) {
  anchor_sim_ns_ = sim_ns;
  anchor_wall_ns_ = wall_ns;
  paced_ = true;
}

void SimPacer::tick(StoneSimulation& sim, std::int64_t wall_ns, UpdateBudget& budget,
                    const Publish& publish) {
  if (!sim.started()) {
    publish(sim.update(sample_ns(0), budget));
    next_k_ = next_sample_after(sim.time_ns());
    anchor(sim.time_ns(), wall_ns);
    return;
  }
  if (sim.paused()) {
    // The time it is given does not matter while paused: only queued ticks are taken.
    if (sim.steps_queued() > 0) publish(sim.update(sim.time_ns(), budget));
    paced_ = false;
    return;
  }
  // After a pause or ~step the pace starts again from where the simulation stands.
  if (!paced_) anchor(sim.time_ns(), wall_ns);
  next_k_ = std::max(next_k_, next_sample_after(sim.time_ns()));
  const std::int64_t target_ns =
      real_time_factor_ > 0.0
          ? anchor_sim_ns_ +
                std::llround(static_cast<double>(wall_ns - anchor_wall_ns_) * real_time_factor_)
          : std::numeric_limits<std::int64_t>::max();
  bool first = true, cut_short = false;
  while (sample_ns(next_k_) <= target_ns) {
    if (!first && budget.spent()) {
      cut_short = true;
      break;
    }
    first = false;
    // A sample period longer than the clock's maximum lag (a slow ~rate) is run in parts: the
    // simulation would otherwise skip ahead instead of stepping.
    const std::int64_t instant_ns = sample_ns(next_k_);
    const std::int64_t now_ns = std::min(instant_ns, sim.time_ns() + sim.max_lag_ns());
    const UpdateResult result = sim.update(now_ns, budget);
    publish(result);
    if (result.steps_deferred > 0) {
      cut_short = true;
      break;
    }
    if (now_ns == instant_ns) ++next_k_;
  }
  // Behind the pace: it restarts from here, so a slow scene runs slower instead of skipping.
  if (cut_short && real_time_factor_ > 0.0) anchor(sim.time_ns(), wall_ns);
}

}  // namespace virtual_go
