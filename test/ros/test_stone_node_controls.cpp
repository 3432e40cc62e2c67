// ~pause, ~step and ~unpause through ROS service clients, and ~publish_clock: checked on what
// the node publishes (odom and tf stamps, /clock, ~events), stepped states against the closed
// form of the motion. No wall-clock asserts: wall time only bounds the waits.
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Empty.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "support/node_observer.h"
#include "support/node_reference.h"
#include "virtual_go/StepSimulation.h"

using vgtest::ClosedForm;
using vgtest::NodeObserver;

namespace {

std::int64_t ns(const ros::Time& t) { return static_cast<std::int64_t>(t.toNSec()); }

// Latest odom stamp, after spinning for `wall_s` seconds.
std::int64_t latest_odom_after(NodeObserver& o, double wall_s) {
  o.wait_until([] { return false; }, wall_s);
  return o.odom.empty() ? 0 : ns(o.odom.back().header.stamp);
}

// The tf at `stamp` agrees with the closed form from `event`.
void expect_tf_on_closed_form(NodeObserver& o, const virtual_go::StoneEvent& event,
                              const ros::Time& stamp, double tolerance = 1e-9) {
  const ClosedForm reference = ClosedForm::from_event(*o.info, event);
  const auto tf = o.tf_at(stamp);
  ASSERT_TRUE(tf) << "no tf at " << stamp;
  const vgtest::MotionState s = reference.at(vgtest::seconds_between(event.header.stamp, stamp));
  EXPECT_LT((s.position - vgtest::vec(tf->transform.translation)).norm(), tolerance);
  EXPECT_LT(vgtest::angle_between(s.orientation, vgtest::quat(tf->transform.rotation)), tolerance);
}

virtual_go::StepSimulation step(std::uint32_t ticks) {
  virtual_go::StepSimulation srv;
  srv.request.ticks = ticks;
  return srv;
}

}  // namespace

TEST(StoneNodeControls, PauseHoldsStepTakesItsTicksUnpauseSkipsThePause) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  std_srvs::Empty empty;
  ASSERT_TRUE(o.call("pause", empty));
  // A tick may be under way when the pause lands: let it pass, then nothing comes.
  const std::int64_t paused_ns = latest_odom_after(o, 0.3);
  const std::size_t events = o.events.size();
  EXPECT_EQ(latest_odom_after(o, 1.0), paused_ns);
  EXPECT_EQ(o.events.size(), events);

  auto ten = step(10);
  ASSERT_TRUE(o.call("step", ten));
  EXPECT_TRUE(ten.response.success) << ten.response.message;
  const std::int64_t stepped_ns = paused_ns + 10 * o.info->dt_ns;
  ASSERT_TRUE(o.wait_until([&] { return ns(o.odom.back().header.stamp) == stepped_ns; }, 5.0))
      << "after ~step 10 the latest odom is at " << ns(o.odom.back().header.stamp) - paused_ns
      << " ns past the pause";
  EXPECT_EQ(latest_odom_after(o, 0.5), stepped_ns);  // and no further
  ros::Time stamp;
  stamp.fromNSec(static_cast<std::uint64_t>(stepped_ns));
  expect_tf_on_closed_form(o, o.events.back(), stamp);

  ASSERT_TRUE(o.call("unpause", empty));
  const auto jump = o.wait_for_event(events);
  ASSERT_TRUE(jump);
  EXPECT_EQ(jump->reason, "time_jump");
  EXPECT_EQ(jump->detail, "unpaused");
  EXPECT_GT(ns(jump->header.stamp), stepped_ns + 1000000000);  // ROS time went on 1.5 s
  // The motion goes on from the stepped state, on the new time line.
  const auto after = o.odom_after(jump->header.stamp, 5);
  ASSERT_GE(after.size(), 5u);
  expect_tf_on_closed_form(o, *jump, after.back().header.stamp);
  const ClosedForm before_pause = ClosedForm::from_event(*o.info, o.events[events - 1]);
  const vgtest::MotionState at_pause =
      before_pause.at(vgtest::seconds_between(o.events[events - 1].header.stamp, stamp));
  EXPECT_LT((at_pause.position - vgtest::vec(jump->pose.position)).norm(), 1e-9);
}

TEST(StoneNodeControls, BadStepsAreRefusedNamingTheLimit) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  auto running = step(5);
  ASSERT_TRUE(o.call("step", running));
  EXPECT_FALSE(running.response.success);
  EXPECT_EQ(running.response.message,
            "refused: ~step needs the simulation paused (call ~pause first)");
  std_srvs::Empty empty;
  ASSERT_TRUE(o.call("pause", empty));
  auto zero = step(0);
  ASSERT_TRUE(o.call("step", zero));
  EXPECT_FALSE(zero.response.success);
  EXPECT_EQ(zero.response.message, "ticks: must be at least 1, got 0");
  auto huge = step(4294967295u);
  ASSERT_TRUE(o.call("step", huge));
  EXPECT_FALSE(huge.response.success);
  EXPECT_EQ(huge.response.message,
            "ticks: at most 1000000 may be queued (0 already are), got 4294967295");
  ASSERT_TRUE(o.call("unpause", empty));
  ASSERT_TRUE(o.call("unpause", empty));  // idempotent
  // Still alive and moving.
  const std::int64_t now_ns = latest_odom_after(o, 0.2);
  EXPECT_GT(latest_odom_after(o, 0.5), now_ns);
}

// The node owns the time (~publish_clock, factor 0) while everyone, itself included, runs on
// use_sim_time: it must not wait for its own /clock.
TEST(StoneNodeOwnClock, ClockAndStatesFollowTheSampleScheduleAndTheControls) {
  std::vector<std::int64_t> clock;
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe<rosgraph_msgs::Clock>(
      "/clock", 10000,
      [&](const rosgraph_msgs::Clock::ConstPtr& m) { clock.push_back(ns(m->clock)); });
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  ASSERT_TRUE(o.wait_until([&] { return clock.size() > 100; }, 10.0));
  for (std::size_t i = 1; i < clock.size(); ++i) ASSERT_GE(clock[i], clock[i - 1]) << i;
  // Every state on the schedule: the grid time at or before 1 s + k / 50 (whole ms at 50 Hz).
  const std::int64_t dt_ns = o.info->dt_ns;
  for (const auto& m : o.odom) {
    const std::int64_t t = ns(m.header.stamp) - 1000000000;
    EXPECT_EQ(t % dt_ns, 0) << t;
  }
  std::size_t on_schedule = 0;
  for (const auto& m : o.odom) on_schedule += (ns(m.header.stamp) - 1000000000) % 20000000 == 0;
  EXPECT_GT(on_schedule, o.odom.size() * 9 / 10);  // a few where a tick's budget ran out

  std_srvs::Empty empty;
  ASSERT_TRUE(o.call("pause", empty));
  o.wait_until([] { return false; }, 0.3);
  const std::int64_t paused_ns = clock.back();
  const std::size_t seen = clock.size();
  o.wait_until([] { return false; }, 1.0);
  ASSERT_GT(clock.size(), seen);  // /clock is repeated while paused, for late subscribers
  for (std::size_t i = seen; i < clock.size(); ++i) EXPECT_EQ(clock[i], paused_ns);
  EXPECT_EQ(ns(o.odom.back().header.stamp), paused_ns);  // /clock = the latest state's stamp

  auto seven = step(7);
  ASSERT_TRUE(o.call("step", seven));
  EXPECT_TRUE(seven.response.success) << seven.response.message;
  ASSERT_TRUE(o.wait_until([&] { return clock.back() == paused_ns + 7 * dt_ns; }, 5.0));
  ros::Time stamp;
  stamp.fromNSec(static_cast<std::uint64_t>(paused_ns + 7 * dt_ns));
  expect_tf_on_closed_form(o, o.events.back(), stamp);

  const std::size_t events = o.events.size();
  ASSERT_TRUE(o.call("unpause", empty));
  ASSERT_TRUE(o.wait_until([&] { return clock.back() > paused_ns + 10000000000; }, 10.0));
  // Owning the clock, unpausing is no time jump: the motion just goes on.
  for (std::size_t i = events; i < o.events.size(); ++i) EXPECT_NE(o.events[i].reason, "time_jump");
  // Simulated minutes from the segment's start at factor 0: two closed forms drift apart. At
  // the latest transform the listener holds: at factor 0 the node publishes faster than the
  // listener's queue may take, and a transform asked for at a stamp whose message was dropped is
  // interpolated between the neighbours it has (a slerp across the tumbling stone's turn: once
  // 0.18 rad off, the position, linear in time, exact).
  const auto latest = o.latest_tf();
  ASSERT_TRUE(latest);
  expect_tf_on_closed_form(o, o.events.back(), latest->header.stamp, 1e-7);
}
