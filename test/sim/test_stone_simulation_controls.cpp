// StoneSimulation's controls (~pause, ~step, ~unpause), without ROS: while paused nothing
// moves bit for bit however ROS time goes; ~step takes exactly the ticks asked, on the dt grid,
// with the states of the closed-form flight; unpausing skips the paused interval when the
// simulation follows ROS time (a time_jump "unpaused"), and simply goes on when it owns the
// clock (~publish_clock). Bad requests are refused with their limit and change nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/sim/stone_simulation.h"

namespace vg = virtual_go;

namespace {

constexpr std::int64_t kStart = 1700000000123456789;  // a realistic wall-clock stamp, ns
constexpr std::int64_t kMs = 1000000;

// An off-axis spinning toss without the board: its state at any time has a closed form.
vg::StoneConfig spinning_toss() {
  vg::StoneConfig c;
  c.initial_position_world = Eigen::Vector3d(0.0, 0.0, 0.02);
  c.initial_orientation_xyzw = Eigen::Vector4d(0.2588190, 0.0, 0.0, 0.9659258);
  c.initial_velocity_world = Eigen::Vector3d(0.1, 0.0, 1.0);
  c.initial_angular_velocity_world = Eigen::Vector3d(7.0, -3.0, 45.0);
  return c;
}

// Spent once `steps` steps were taken (the first is free).
class StepBudget : public vg::UpdateBudget {
 public:
  explicit StepBudget(int steps) : left_(steps) {}
  bool spent() override { return --left_ <= 0; }

 private:
  int left_;
};

// The state `sim` shows at stamp_ns agrees with the closed form of the flight from kStart.
void expect_closed_form(const vg::StoneSimulation& sim, std::int64_t stamp_ns) {
  const vg::ExactMotion exact(sim.setup(), sim.initial_state());
  const vg::RigidBodyState ref = exact.state_at(vg::seconds_between(kStart, stamp_ns));
  EXPECT_LT((ref.position_world - sim.state().position_world).norm(), 1e-9);
  EXPECT_LT(vg::orientation_error(ref.orientation, sim.state().orientation), 1e-10);
}

}  // namespace

TEST(StoneSimulationControls, PauseHoldsTimeAndStateBitwiseWhateverRosTimeDoes) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  sim.update(kStart + 100 * kMs);
  EXPECT_EQ(sim.pause().rfind("paused at", 0), 0u);
  EXPECT_TRUE(sim.paused());
  const vg::RigidBodyState state = sim.state();
  const vg::StateOutput output = sim.output();
  const std::int64_t time_ns = sim.time_ns();
  // A request waits for the next step, which does not come while paused.
  EXPECT_EQ(sim.set_angular_velocity(Eigen::Vector3d(0, 0, 20), "world"),
            "applied at the next physics step");
  std::int64_t now = kStart + 100 * kMs;
  for (int tick = 0; tick < 5000; ++tick) {
    now += 16 * kMs + (tick % 5) * 77777;  // 80 s of jittery ticks, then a jump back and forth
    const std::int64_t ros_ns = tick == 4000   ? kStart - 10 * kMs
                                : tick == 4001 ? now + 5000 * kMs
                                               : now;
    const vg::UpdateResult r = sim.update(ros_ns);
    ASSERT_FALSE(r.advanced) << tick;
    ASSERT_TRUE(r.events.empty()) << tick;
  }
  EXPECT_TRUE(sim.state() == state);
  EXPECT_EQ(sim.output().position_world, output.position_world);
  EXPECT_EQ(sim.output().orientation.coeffs(), output.orientation.coeffs());
  EXPECT_EQ(sim.time_ns(), time_ns);
  EXPECT_EQ(sim.pending_requests(), 1u);
  EXPECT_EQ(sim.pause(), "already paused");
}

TEST(StoneSimulationControls, StepAdvancesExactlyTheTicksAskedOnTheGrid) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  sim.update(kStart + 250 * kMs);
  sim.pause();
  const std::int64_t paused_at = sim.time_ns();
  ASSERT_EQ(paused_at, kStart + 250 * kMs);
  EXPECT_EQ(sim.step(10).rfind("10 tick(s) of 1000000 ns queued", 0), 0u);
  EXPECT_EQ(sim.steps_queued(), 10);
  // ROS time does not matter while paused: not even one that went back.
  const vg::UpdateResult r = sim.update(kStart + 5 * kMs);
  EXPECT_TRUE(r.advanced);
  EXPECT_TRUE(r.events.empty());
  EXPECT_EQ(r.stamp_ns, paused_at + 10 * sim.dt_ns());
  EXPECT_EQ(sim.time_ns(), paused_at + 10 * sim.dt_ns());
  EXPECT_EQ(r.steps_deferred, 0);  // not behind ROS time: stepping is not a lag
  EXPECT_EQ(sim.steps_queued(), 0);
  expect_closed_form(sim, r.stamp_ns);
  // Nothing more until the next ~step.
  EXPECT_FALSE(sim.update(kStart + 10000 * kMs).advanced);
  EXPECT_EQ(sim.time_ns(), paused_at + 10 * kMs);

  // A budget spreads many ticks over updates; each update's stamp is on the grid.
  sim.step(1000);
  std::int64_t expected_ns = sim.time_ns(), updates = 0;
  while (sim.steps_queued() > 0) {
    StepBudget seven(7);
    const vg::UpdateResult part = sim.update(0, seven);
    const std::int64_t taken = std::min<std::int64_t>(7, 1000 - 7 * updates);
    expected_ns += taken * sim.dt_ns();
    ASSERT_EQ(part.stamp_ns, expected_ns) << updates;
    ++updates;
  }
  EXPECT_EQ(updates, 143);  // ceil(1000 / 7)
  EXPECT_EQ(sim.time_ns(), paused_at + 1010 * kMs);
  expect_closed_form(sim, sim.time_ns());
}

TEST(StoneSimulationControls, RequestsQueuedWhilePausedApplyAtTheFirstStep) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  sim.update(kStart + 300 * kMs);
  sim.pause();
  sim.reset();
  sim.update(kStart + 900 * kMs);
  EXPECT_EQ(sim.pending_requests(), 1u);
  sim.step(1);
  const vg::UpdateResult r = sim.update(kStart + 900 * kMs);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].reason, vg::EventReason::reset);
  EXPECT_EQ(r.events[0].stamp_ns, kStart + 301 * kMs);
  EXPECT_TRUE(sim.state() == sim.initial_state());
  EXPECT_EQ(sim.pending_requests(), 0u);
}

// Following ROS time, the paused interval is skipped: one time_jump "unpaused" at the ROS time
// of the next update, the state going on from where it stood; then the flight continues from
// it on the new grid.
TEST(StoneSimulationControls, UnpauseFollowingRosTimeSkipsThePausedInterval) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  sim.update(kStart + 200 * kMs);
  sim.pause();
  sim.step(3);
  sim.update(kStart + 300 * kMs);
  const vg::RigidBodyState state = sim.state();
  EXPECT_EQ(sim.unpause().rfind("unpaused at", 0), 0u);
  EXPECT_EQ(sim.unpause(), "not paused");
  const std::int64_t now = kStart + 5000 * kMs + 123;
  const vg::UpdateResult r = sim.update(now);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].reason, vg::EventReason::time_jump);
  EXPECT_EQ(r.events[0].detail, "unpaused");
  EXPECT_EQ(r.events[0].stamp_ns, now);
  EXPECT_TRUE(r.advanced);
  EXPECT_EQ(r.stamp_ns, now);
  EXPECT_TRUE(sim.state() == state);
  // The motion goes on from the paused state: 203 ms of flight after `now` + 50 ms.
  sim.update(now + 50 * kMs);
  const vg::ExactMotion exact(sim.setup(), sim.initial_state());
  const vg::RigidBodyState ref = exact.state_at(0.253);
  EXPECT_LT((ref.position_world - sim.state().position_world).norm(), 1e-9);
}

TEST(StoneSimulationControls, UnpauseBeforeRosTimeMovesOnIsNoJump) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  sim.pause();
  sim.unpause();
  EXPECT_FALSE(sim.update(kStart + kMs / 2).advanced);  // not a step later: in step
  const vg::UpdateResult r = sim.update(kStart + 2 * kMs);
  EXPECT_TRUE(r.events.empty());
  EXPECT_EQ(r.stamp_ns, kStart + 2 * kMs);
}

// Owning the clock, the simulation's time is the only time: unpausing goes on where it stood.
TEST(StoneSimulationControls, UnpauseOwningTheClockContinuesWithoutAJump) {
  vg::StoneConfig c = spinning_toss();
  c.publish_clock = true;
  c.real_time_factor = 0.0;
  vg::StoneSimulation sim(c);
  sim.update(kStart);
  sim.update(kStart + 40 * kMs);
  sim.pause();
  sim.step(2);
  sim.update(0);
  sim.unpause();
  const vg::UpdateResult r = sim.update(kStart + 45 * kMs);
  EXPECT_TRUE(r.events.empty());
  EXPECT_EQ(r.stamp_ns, kStart + 45 * kMs);
  expect_closed_form(sim, r.stamp_ns);
}

TEST(StoneSimulationControls, BadStepsAreRefusedWithTheLimitAndChangeNothing) {
  vg::StoneSimulation sim(spinning_toss());
  sim.update(kStart);
  try {
    sim.step(5);
    FAIL() << "stepping while running";
  } catch (const vg::RequestRefused& e) {
    EXPECT_NE(std::string(e.what()).find("~pause"), std::string::npos) << e.what();
  }
  sim.pause();
  try {
    sim.step(0);
    FAIL() << "0 ticks";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "ticks");
    EXPECT_EQ(std::string(e.what()), "ticks: must be at least 1, got 0");
  }
  sim.step(vg::kMaxStepTicks - 5);
  try {
    sim.step(6);
    FAIL() << "beyond the limit";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()),
              "ticks: at most 1000000 may be queued (999995 already are), got 6");
  }
  EXPECT_EQ(sim.steps_queued(), vg::kMaxStepTicks - 5);
  EXPECT_EQ(sim.time_ns(), kStart);
  // Unpausing drops what was queued, and says so.
  EXPECT_NE(sim.unpause().find("999995 tick(s) ~step queued are dropped"), std::string::npos);
  EXPECT_EQ(sim.steps_queued(), 0);
}

TEST(StoneSimulationControls, RealTimeFactorIsCheckedWithItsLimits) {
  vg::StoneConfig c;
  c.real_time_factor = 2.0;
  try {
    vg::check_config(c);
    FAIL() << "a factor without ~publish_clock";
  } catch (const vg::ConfigError& e) {
    EXPECT_EQ(e.field(), "~real_time_factor");
    EXPECT_NE(std::string(e.what()).find("needs ~publish_clock true"), std::string::npos);
  }
  c.publish_clock = true;
  for (double bad : {-1.0, 1e-4, 1001.0, std::nan("")}) {
    c.real_time_factor = bad;
    try {
      vg::check_config(c);
      FAIL() << bad;
    } catch (const vg::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("must be 0 (as fast as possible) or between 0.001 and "
                                           "1000"),
                std::string::npos)
          << e.what();
    }
  }
  for (double good : {0.0, 0.001, 1.0, 1000.0}) {
    c.real_time_factor = good;
    EXPECT_NO_THROW(vg::check_config(c)) << good;
  }
}
