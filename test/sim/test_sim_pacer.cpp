// SimPacer: the simulation owning its clock (~publish_clock). Checked against closed forms of
// the schedule it promises: every published stamp is the dt grid time at or before a sample
// instant 1 s + k / rate (k whole), at factor 0 one wall tick runs as far as its budget allows,
// at factor f the simulated time after W of wall time is the last sample at or before 1 s + f W,
// and pausing, stepping and unpausing neither skip nor repeat a tick. The states are those of
// the closed-form flight. Wall time is driven by hand: no wall clock is read.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/sim/sim_pacer.h"

namespace vg = virtual_go;

namespace {

constexpr std::int64_t kMs = 1000000;
constexpr std::int64_t kWall0 = 5000 * kMs;  // any monotonic clock's reading

vg::StoneConfig own_clock(double real_time_factor) {
  vg::StoneConfig c;
  c.publish_clock = true;
  c.real_time_factor = real_time_factor;
  c.rate_hz = 60.0;
  c.initial_position_world = Eigen::Vector3d(0.0, 0.0, 0.02);
  c.initial_velocity_world = Eigen::Vector3d(0.1, 0.0, 1.0);
  c.initial_angular_velocity_world = Eigen::Vector3d(7.0, -3.0, 45.0);
  return c;
}

// Spent after `questions` questions.
class Questions : public vg::UpdateBudget {
 public:
  explicit Questions(long questions) : left_(questions) {}
  bool spent() override { return left_-- <= 0; }

 private:
  long left_;
};

// The grid time at or before sample k of a 60 Hz schedule from 1 s with dt 1 ms, written out:
// 1 s + floor(round(k * 1e9 / 60) / 1e6) ms.
std::int64_t grid_sample_ns(std::int64_t k) {
  const std::int64_t instant_ns = std::llround(static_cast<double>(k) * 1e9 / 60.0);
  return 1000 * kMs + instant_ns / kMs * kMs;
}

struct Published {
  std::vector<std::int64_t> stamps;
  std::vector<vg::SegmentEvent> events;
  vg::SimPacer::Publish into() {
    return [this](const vg::UpdateResult& r) {
      if (r.advanced) stamps.push_back(r.stamp_ns);
      events.insert(events.end(), r.events.begin(), r.events.end());
    };
  }
};

void expect_closed_form(const vg::StoneSimulation& sim) {
  const vg::ExactMotion exact(sim.setup(), sim.initial_state());
  const vg::RigidBodyState ref =
      exact.state_at(vg::seconds_between(vg::kOwnClockStartNs, sim.time_ns()));
  EXPECT_LT((ref.position_world - sim.state().position_world).norm(), 1e-9);
  EXPECT_LT(vg::orientation_error(ref.orientation, sim.state().orientation), 1e-10);
}

}  // namespace

TEST(SimPacer, FactorZeroRunsManySamplesPerTickOnTheClosedFormGrid) {
  vg::StoneSimulation sim(own_clock(0.0));
  vg::SimPacer pacer(60.0, 0.0);
  Published out;
  vg::UnlimitedBudget unlimited;
  pacer.tick(sim, kWall0, unlimited, out.into());  // the start, at 1 s
  ASSERT_EQ(out.stamps.size(), 1u);
  EXPECT_EQ(out.stamps[0], vg::kOwnClockStartNs);
  ASSERT_EQ(out.events.size(), 1u);
  EXPECT_EQ(out.events[0].reason, vg::EventReason::start);
  // One tick whose budget answers 20,000 questions: one per step after an update's first and
  // one per update after the tick's first, so sample k (S(k) = floor(k * 50 / 3) ms of steps
  // from the start) is complete after S(k) - 1 questions: 1,200 samples (20 s, 19,999
  // questions), then the 20,000th lets sample 1,201 begin and its second step is refused.
  Questions budget(20000);
  pacer.tick(sim, kWall0 + kMs, budget, out.into());
  ASSERT_EQ(out.stamps.size(), 1u + 1200u + 1u);
  for (std::size_t k = 1; k <= 1200; ++k) {
    ASSERT_EQ(out.stamps[k], grid_sample_ns(static_cast<std::int64_t>(k))) << k;
  }
  // Where the budget ran out, a state on the grid is published too (the node's /clock never
  // runs ahead of the states).
  EXPECT_EQ(out.stamps.back(), vg::kOwnClockStartNs + 20001 * kMs);
  EXPECT_EQ(out.events.size(), 1u);  // no time jump: the pacer never outruns the clock's lag
  expect_closed_form(sim);
  // The next tick finishes that sample and goes on with the schedule: 100 questions complete
  // samples 1,201 to 1,206 (14 + 16 + 16 + 15 + 16 + 16 questions, 1 per sample between) and
  // stop sample 1,207 after 2 steps.
  Questions more(100);
  pacer.tick(sim, kWall0 + 2 * kMs, more, out.into());
  ASSERT_EQ(out.stamps.size(), 1u + 1200u + 1u + 6u + 1u);
  for (std::int64_t k = 1201; k <= 1206; ++k) {
    EXPECT_EQ(out.stamps[static_cast<std::size_t>(k + 1)], grid_sample_ns(k)) << k;
  }
  EXPECT_EQ(out.stamps.back(), grid_sample_ns(1206) + 2 * kMs);
  expect_closed_form(sim);
}

TEST(SimPacer, PositiveFactorKeepsSimulatedTimeAtFactorTimesWallTime) {
  for (double factor : {1.0, 2.5, 0.1}) {
    vg::StoneSimulation sim(own_clock(factor));
    vg::SimPacer pacer(60.0, factor);
    Published out;
    vg::UnlimitedBudget unlimited;
    std::int64_t wall = kWall0;
    pacer.tick(sim, wall, unlimited, out.into());
    for (int tick = 1; tick <= 300; ++tick) {
      wall += 16 * kMs + (tick % 3) * 400000;  // a jittery 60 Hz wall timer
      pacer.tick(sim, wall, unlimited, out.into());
      // The last sample at or before 1 s + f (wall - wall0), on the grid.
      const double target_ns = 1e9 + factor * static_cast<double>(wall - kWall0);
      const auto k = static_cast<std::int64_t>(std::floor((target_ns - 1e9) * 60.0 / 1e9));
      ASSERT_EQ(sim.time_ns(), grid_sample_ns(k)) << factor << " " << tick;
    }
    EXPECT_EQ(out.events.size(), 1u) << factor;
    expect_closed_form(sim);
  }
}

TEST(SimPacer, PauseStepAndUnpauseNeitherSkipNorRepeatATick) {
  vg::StoneSimulation sim(own_clock(1.0));
  vg::SimPacer pacer(60.0, 1.0);
  Published out;
  vg::UnlimitedBudget unlimited;
  std::int64_t wall = kWall0;
  pacer.tick(sim, wall, unlimited, out.into());
  wall += 100 * kMs;
  pacer.tick(sim, wall, unlimited, out.into());
  const std::int64_t paused_at = sim.time_ns();
  EXPECT_EQ(paused_at, grid_sample_ns(6));
  sim.pause();
  const std::size_t published = out.stamps.size();
  for (int tick = 0; tick < 100; ++tick) {
    wall += 16 * kMs;
    pacer.tick(sim, wall, unlimited, out.into());
  }
  EXPECT_EQ(out.stamps.size(), published);
  EXPECT_EQ(sim.time_ns(), paused_at);
  sim.step(7);
  wall += 16 * kMs;
  pacer.tick(sim, wall, unlimited, out.into());
  EXPECT_EQ(out.stamps.back(), paused_at + 7 * kMs);
  sim.unpause();
  // From here the pace starts again: 50 ms of wall time later, the samples of 50 ms.
  wall += 16 * kMs;
  pacer.tick(sim, wall, unlimited, out.into());
  EXPECT_EQ(sim.time_ns(), paused_at + 7 * kMs);  // the tick that anchors the pace
  wall += 50 * kMs;
  pacer.tick(sim, wall, unlimited, out.into());
  // Samples are at 1 s + k / 60; the last at or before paused_at + 7 ms + 50 ms.
  const std::int64_t target = paused_at + 57 * kMs;
  std::int64_t k = 0;
  while (1000 * kMs + std::llround(static_cast<double>(k + 1) * 1e9 / 60.0) <= target) ++k;
  EXPECT_EQ(sim.time_ns(), grid_sample_ns(k));
  for (const vg::SegmentEvent& e : out.events) EXPECT_NE(e.reason, vg::EventReason::time_jump);
  for (std::size_t i = 1; i < out.stamps.size(); ++i) EXPECT_GT(out.stamps[i], out.stamps[i - 1]);
  expect_closed_form(sim);
}

// A sample period longer than the clock's lag (1 s) is stepped in parts, never skipped.
TEST(SimPacer, SlowRateIsSteppedNotSkipped) {
  vg::StoneConfig c = own_clock(0.0);
  c.rate_hz = 0.25;  // a sample every 4 s
  vg::StoneSimulation sim(c);
  vg::SimPacer pacer(0.25, 0.0);
  Published out;
  vg::UnlimitedBudget unlimited;
  pacer.tick(sim, kWall0, unlimited, out.into());
  // 1,000 steps per part (999 questions) and a question between parts: the fifth part's last
  // step is the 4,999th question.
  Questions budget(4999);
  pacer.tick(sim, kWall0 + kMs, budget, out.into());
  EXPECT_EQ(sim.time_ns(), vg::kOwnClockStartNs + 5000 * kMs);
  EXPECT_EQ(out.stamps.size(), 1u + 5u);  // a state at the end of every part
  EXPECT_EQ(out.events.size(), 1u);
  expect_closed_form(sim);
}
