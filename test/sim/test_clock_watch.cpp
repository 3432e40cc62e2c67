// ClockWatch: a stall of ROS time against wall time is reported once, a moving clock never, and
// a clock that moves again after a reported stall is reported once too.
#include <gtest/gtest.h>

#include <vector>

#include "virtual_go/common/validation.h"
#include "virtual_go/sim/clock_watch.h"

namespace vg = virtual_go;
using Change = vg::ClockWatch::Change;

namespace {
constexpr std::int64_t kS = 1000000000;  // ns per s
constexpr std::int64_t kTick = kS / 2;   // the node looks every 0.5 s
}  // namespace

TEST(ClockWatch, PatienceMustBePositive) {
  EXPECT_THROW(vg::ClockWatch(0), vg::InvalidArgument);
  EXPECT_THROW(vg::ClockWatch(-1), vg::InvalidArgument);
  EXPECT_EQ(vg::ClockWatch(3 * kS).patience_ns(), 3 * kS);
}

TEST(ClockWatch, NoClockYetIsReportedOnceAfterThePatience) {
  vg::ClockWatch watch(3 * kS);
  const std::int64_t wall0 = 1234 * kS;  // any origin: only differences count
  int stalls = 0;
  for (std::int64_t t = 0; t <= 60 * kS; t += kTick) {
    const Change change = watch.observe(wall0 + t, 0);
    if (t < 3 * kS) {
      EXPECT_EQ(change, Change::none) << "at " << t << " ns";
    }
    if (t == 3 * kS) {
      EXPECT_EQ(change, Change::stalled);
    }
    stalls += change == Change::stalled;
    EXPECT_NE(change, Change::resumed);
  }
  EXPECT_EQ(stalls, 1);
}

TEST(ClockWatch, MovingClockIsNeverAStall) {
  vg::ClockWatch watch(3 * kS);
  // /clock at any pace, even far slower than wall time, as long as it moves between looks.
  for (std::int64_t t = 0; t <= 100 * kS; t += kTick) {
    EXPECT_EQ(watch.observe(t, 5 * kS + t / 1000 + 1), Change::none);
  }
}

TEST(ClockWatch, StallThenMoveThenStallAgain) {
  vg::ClockWatch watch(3 * kS);
  std::int64_t wall = 0;
  std::int64_t ros = 100 * kS;
  for (; wall < 5 * kS; wall += kTick, ros += kTick)
    EXPECT_EQ(watch.observe(wall, ros), Change::none);
  // The clock stops at `ros`: reported once, 3 s after it was last seen moving.
  const std::int64_t stopped_at = wall;
  std::vector<std::int64_t> stalled_at;
  for (; wall < stopped_at + 10 * kS; wall += kTick) {
    if (watch.observe(wall, ros) == Change::stalled) stalled_at.push_back(wall);
  }
  ASSERT_EQ(stalled_at.size(), 1u);
  EXPECT_EQ(stalled_at[0], stopped_at + 3 * kS);
  // It moves: resumed, once.
  EXPECT_EQ(watch.observe(wall, ros + 1), Change::resumed);
  EXPECT_EQ(watch.observe(wall + kTick, ros + 2), Change::none);
  // A jump back in time (a looping bag) is movement too.
  EXPECT_EQ(watch.observe(wall + 2 * kTick, ros - 50 * kS), Change::none);
  // And a second stall is reported again.
  int stalls = 0;
  for (std::int64_t t = wall + 3 * kTick; t < wall + 20 * kS; t += kTick) {
    stalls += watch.observe(t, ros - 50 * kS) == Change::stalled;
  }
  EXPECT_EQ(stalls, 1);
}
