// SimClock: whole-nanosecond grid, accumulator semantics, time jumps.
#include <gtest/gtest.h>

#include "virtual_go/common/validation.h"
#include "virtual_go/sim/sim_clock.h"

namespace vg = virtual_go;
using Action = vg::SimClock::Action;

TEST(SimClock, WaitsForValidTimeThenStartsAtIt) {
  vg::SimClock clock(1000000, 1000000000);
  EXPECT_EQ(clock.plan(0).action, Action::wait);  // use_sim_time before the first /clock
  EXPECT_EQ(clock.plan(5).action, Action::start);
  clock.restart(5);
  EXPECT_TRUE(clock.started());
  EXPECT_EQ(clock.time_ns(), 5);
}

TEST(SimClock, StepsToTheLatestGridPointAndKeepsTheRemainder) {
  vg::SimClock clock(1000000, 1000000000);
  clock.restart(1000);
  EXPECT_EQ(clock.plan(1000).action, Action::wait);  // same ROS time twice: nothing new
  EXPECT_EQ(clock.plan(1000 + 999999).action, Action::wait);
  vg::SimClock::Plan p = clock.plan(1000 + 2500000);
  EXPECT_EQ(p.action, Action::advance);
  EXPECT_EQ(p.steps, 2);
  clock.step();
  clock.step();
  EXPECT_EQ(clock.time_ns(), 1000 + 2000000);
  // The half step left over is taken at the next tick, not lost.
  p = clock.plan(1000 + 3000000);
  EXPECT_EQ(p.action, Action::advance);
  EXPECT_EQ(p.steps, 1);
}

TEST(SimClock, GridDoesNotDependOnTickTimes) {
  // Two tick patterns reach the same grid times: results do not depend on timer jitter.
  const std::int64_t dt = 333333;
  vg::SimClock a(dt, 1000000000), b(dt, 1000000000);
  a.restart(7);
  b.restart(7);
  for (std::int64_t now : {1000000, 1700000, 2100000, 9000000}) {
    const auto p = a.plan(now);
    for (std::int64_t i = 0; i < p.steps; ++i) a.step();
  }
  const auto p = b.plan(9000000);
  for (std::int64_t i = 0; i < p.steps; ++i) b.step();
  EXPECT_EQ(a.time_ns(), b.time_ns());
  EXPECT_EQ((a.time_ns() - 7) % dt, 0);
}

TEST(SimClock, DetectsBackwardAndLargeForwardJumps) {
  vg::SimClock clock(1000000, 1000000000);
  clock.restart(5000000000);
  EXPECT_EQ(clock.plan(4000000000).action, Action::jump_back);
  EXPECT_EQ(clock.plan(4999999999).action, Action::jump_back);
  EXPECT_EQ(clock.plan(6000000000).action, Action::advance);
  EXPECT_EQ(clock.plan(6000000001).action, Action::jump_forward);
  clock.restart(4000000000);
  EXPECT_EQ(clock.time_ns(), 4000000000);
}

TEST(SimClock, RejectsBadSteps) {
  EXPECT_THROW(vg::SimClock(0, 10), vg::InvalidArgument);
  EXPECT_THROW(vg::SimClock(-1, 10), vg::InvalidArgument);
  EXPECT_THROW(vg::SimClock(100, 10), vg::InvalidArgument);
}
