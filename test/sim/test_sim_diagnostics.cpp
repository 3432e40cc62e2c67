// What /diagnostics reports, without ROS: UpdateStats' rates and means from hand-made update
// costs and simulated times, and diagnostic_report's level and values from simulations driven
// into each state (running, resting on the board, behind, held).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "virtual_go/sim/sim_diagnostics.h"

namespace vg = virtual_go;

namespace {

constexpr std::int64_t kStart = 1700000000123456789;  // a realistic wall-clock stamp, ns
constexpr std::int64_t kMs = 1000000;
constexpr std::int64_t kS = 1000000000;

// Stops an update after a given number of steps.
class FewSteps : public vg::UpdateBudget {
 public:
  explicit FewSteps(int steps) : left_(steps) {}
  bool spent() override { return left_-- <= 1; }

 private:
  int left_;
};

vg::UpdateResult with_events(int n) {
  vg::UpdateResult r;
  r.events.resize(static_cast<std::size_t>(n));
  return r;
}

std::map<std::string, std::string> values(const vg::DiagnosticReport& report) {
  return {report.values.begin(), report.values.end()};
}

}  // namespace

TEST(UpdateStats, RatesAndCostsOverAPeriod) {
  const std::int64_t wall0 = 5 * kS;
  vg::UpdateStats stats(wall0);
  // Three updates costing 1, 2 and 6 ms with 1 + 0 + 2 events; simulated time goes from
  // kStart to kStart + 0.5 s while 2 s of wall time pass.
  stats.record(1 * kMs, with_events(1), kStart);
  stats.record(2 * kMs, with_events(0), kStart + 200 * kMs);
  stats.record(6 * kMs, with_events(2), kStart + 500 * kMs);
  const vg::UpdateSummary s = stats.take(wall0 + 2 * kS);
  EXPECT_DOUBLE_EQ(s.period_s, 2.0);
  EXPECT_EQ(s.updates, 3);
  EXPECT_EQ(s.events, 3);
  EXPECT_DOUBLE_EQ(s.events_per_s, 1.5);
  EXPECT_DOUBLE_EQ(s.step_cost_mean_s, 3e-3);
  EXPECT_DOUBLE_EQ(s.step_cost_max_s, 6e-3);
  // The first update's simulated time is where the period's simulated time starts.
  EXPECT_DOUBLE_EQ(s.real_time_factor, 0.25);

  // The next period starts where this one ended, in wall and in simulated time.
  stats.record(4 * kMs, with_events(0), kStart + 1500 * kMs);
  const vg::UpdateSummary next = stats.take(wall0 + 3 * kS);
  EXPECT_DOUBLE_EQ(next.real_time_factor, 1.0);
  EXPECT_DOUBLE_EQ(next.step_cost_max_s, 4e-3);
  EXPECT_EQ(next.updates, 1);
}

TEST(UpdateStats, EmptyPeriodsAndTheTimeBeforeTheStartReportZero) {
  vg::UpdateStats stats(kS);
  const vg::UpdateSummary none = stats.take(kS);  // no wall time: no division by it
  EXPECT_EQ(none.events_per_s, 0.0);
  EXPECT_EQ(none.real_time_factor, 0.0);
  EXPECT_EQ(none.step_cost_mean_s, 0.0);
  // Before a valid ROS time the simulation has no time (0); the period's simulated time counts
  // from the first state, not from 0 (which would give a factor of ~1.7e9).
  stats.record(kMs, with_events(0), 0);
  stats.record(kMs, with_events(1), kStart);
  stats.record(kMs, with_events(0), kStart + 100 * kMs);
  const vg::UpdateSummary s = stats.take(2 * kS);
  EXPECT_DOUBLE_EQ(s.real_time_factor, 0.1);
  const vg::UpdateSummary idle = stats.take(3 * kS);
  EXPECT_EQ(idle.updates, 0);
  EXPECT_EQ(idle.real_time_factor, 0.0);
  EXPECT_EQ(idle.step_cost_max_s, 0.0);
}

TEST(DiagnosticReport, RunningStoneIsOkWithEveryValue) {
  vg::StoneSimulation sim{vg::StoneConfig()};
  vg::UpdateStats stats(0);
  stats.record(kMs, sim.update(kStart), sim.time_ns());
  stats.record(kMs, sim.update(kStart + 16 * kMs), sim.time_ns());
  sim.reset();
  const vg::DiagnosticReport r = vg::diagnostic_report(sim, stats.take(kS));
  EXPECT_EQ(r.level, vg::DiagnosticLevel::ok);
  const std::map<std::string, std::string> v = values(r);
  for (const char* key : {"stones awake", "stones resting", "events per s", "step cost mean (ms)",
                          "step cost max (ms)", "real-time factor", "pending requests",
                          "steps deferred", "behind (s)", "held", "period (s)"}) {
    EXPECT_EQ(v.count(key), 1u) << key;
  }
  EXPECT_EQ(v.at("stones awake"), "1");
  EXPECT_EQ(v.at("stones resting"), "0");
  EXPECT_EQ(v.at("pending requests"), "1");  // the reset waits for the next step
  EXPECT_EQ(v.at("held"), "false");
  EXPECT_EQ(v.at("steps deferred"), "0");
  EXPECT_EQ(v.at("events per s"), "1");  // the start event in 1 s
  EXPECT_EQ(v.at("step cost mean (ms)"), "1");
}

// The board scene without auto reset, the stone lying flat 2 cm above the board.
vg::StoneConfig drop_onto_board() {
  vg::StoneConfig c;
  c.board_enabled = true;
  c.auto_reset_period_s = 0.0;
  const vg::Stone stone = vg::make_stone(c.stone);
  c.initial_position_world = Eigen::Vector3d(0.0, 0.0, 0.5 * stone.shape.height() + 0.02);
  return c;
}

TEST(DiagnosticReport, StoneAtRestOnTheBoardCountsAsResting) {
  vg::StoneSimulation sim(drop_onto_board());
  sim.update(kStart);
  vg::UpdateStats stats(0);
  EXPECT_EQ(values(vg::diagnostic_report(sim, stats.take(0))).at("stones awake"), "1");
  // A 2 cm drop settles well within 2 s (ticks of 16 ms: a longer gap would be a time jump).
  for (std::int64_t t = kStart; t <= kStart + 2 * kS; t += 16 * kMs) sim.update(t);
  ASSERT_TRUE(sim.world()->is_resting(0));
  const vg::DiagnosticReport r = vg::diagnostic_report(sim, stats.take(0));
  EXPECT_EQ(values(r).at("stones awake"), "0");
  EXPECT_EQ(values(r).at("stones resting"), "1");
  EXPECT_EQ(r.level, vg::DiagnosticLevel::ok);
}

// Stones added by ~place count too: awake while they fall, resting once they rest.
TEST(DiagnosticReport, PlacedStonesAreCounted) {
  vg::StoneSimulation sim(drop_onto_board());
  sim.update(kStart);
  std::string answer;
  vg::PlaceRequest set_down;
  set_down.point = "D4";
  set_down.color = "black";
  (void)sim.place(set_down, answer);
  vg::PlaceRequest dropped;
  dropped.point = "Q16";
  dropped.color = "white";
  dropped.drop_height_m = 0.01;
  (void)sim.place(dropped, answer);
  sim.update(kStart + 16 * kMs);
  vg::UpdateStats stats(0);
  const auto falling = values(vg::diagnostic_report(sim, stats.take(0)));
  // The initial stone and the white one fall; the black one was set down at rest.
  EXPECT_EQ(falling.at("stones awake"), "2");
  EXPECT_EQ(falling.at("stones resting"), "1");
  for (std::int64_t t = kStart; t <= kStart + 2 * kS; t += 16 * kMs) sim.update(t);
  const vg::DiagnosticReport r = vg::diagnostic_report(sim, stats.take(0));
  EXPECT_EQ(values(r).at("stones awake"), "0");
  EXPECT_EQ(values(r).at("stones resting"), "3");
  EXPECT_EQ(r.message, "running; all 3 stones rest");
}

TEST(DiagnosticReport, WarnsWhileThePhysicsFallsBehind) {
  vg::StoneSimulation sim{vg::StoneConfig()};
  vg::UpdateStats stats(0);
  stats.record(kMs, sim.update(kStart), sim.time_ns());
  FewSteps three(3);
  stats.record(kMs, sim.update(kStart + 10 * kMs, three), sim.time_ns());
  const vg::DiagnosticReport behind = vg::diagnostic_report(sim, stats.take(kS));
  EXPECT_EQ(behind.level, vg::DiagnosticLevel::warn);
  EXPECT_EQ(values(behind).at("steps deferred"), "7");
  EXPECT_EQ(values(behind).at("behind (s)"), "0.007");
  // Caught up: OK again.
  stats.record(kMs, sim.update(kStart + 10 * kMs), sim.time_ns());
  EXPECT_EQ(vg::diagnostic_report(sim, stats.take(2 * kS)).level, vg::DiagnosticLevel::ok);
}

TEST(DiagnosticReport, ErrorWithTheCauseWhileHeld) {
  // The default scene from a state check_config refuses: it overflows within a few steps.
  vg::CheckedConfig checked = vg::check_config(vg::StoneConfig());
  checked.initial_state.position_world = Eigen::Vector3d(1.79e308, 0, 0);
  checked.initial_state.velocity_world = Eigen::Vector3d(1.7e308, 0, 0);
  vg::StoneSimulation sim(checked);
  vg::UpdateStats stats(0);
  sim.update(kStart);
  const vg::UpdateResult failed = sim.update(kStart + 100 * kMs);
  ASSERT_FALSE(failed.error.empty());
  const vg::DiagnosticReport r = vg::diagnostic_report(sim, stats.take(kS));
  EXPECT_EQ(r.level, vg::DiagnosticLevel::error);
  EXPECT_NE(r.message.find(sim.failure()), std::string::npos) << r.message;
  EXPECT_EQ(values(r).at("held"), "true");
  sim.set_state(Eigen::Vector3d::Zero(), Eigen::Vector4d(0, 0, 0, 1), Eigen::Vector3d::Zero(),
                Eigen::Vector3d::Zero());
  sim.update(kStart + 200 * kMs);
  EXPECT_EQ(vg::diagnostic_report(sim, stats.take(2 * kS)).level, vg::DiagnosticLevel::ok);
}

// ~pause shows on /diagnostics: "paused" with the queued ~step ticks, at the level of the state
// otherwise (paused is no fault).
TEST(DiagnosticReport, PausedSaysSoWithTheQueuedTicks) {
  vg::StoneSimulation sim{vg::StoneConfig()};
  vg::UpdateStats stats(0);
  stats.record(kMs, sim.update(kStart), sim.time_ns());
  sim.pause();
  sim.step(25);
  const vg::DiagnosticReport r = vg::diagnostic_report(sim, stats.take(kS));
  EXPECT_EQ(r.level, vg::DiagnosticLevel::ok);
  EXPECT_EQ(r.message.rfind("paused at ", 0), 0u) << r.message;
  EXPECT_NE(r.message.find("(25 ~step tick(s) queued)"), std::string::npos) << r.message;
  EXPECT_EQ(values(r).at("paused"), "true");
  EXPECT_EQ(values(r).at("steps queued"), "25");
  sim.unpause();
  EXPECT_EQ(values(vg::diagnostic_report(sim, stats.take(2 * kS))).at("paused"), "false");
}
