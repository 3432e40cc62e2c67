// Simulated ROS time: this test drives /clock (use_sim_time is set in the launch file) and
// checks the publish rate per simulated second, the stamps, tf against the closed form, and a
// backwards jump of the clock (a looping bag).
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>

#include "support/node_observer.h"
#include "support/node_reference.h"

using vgtest::NodeObserver;

namespace {

class ClockDriver {
 public:
  ClockDriver() : pub_(ros::NodeHandle().advertise<rosgraph_msgs::Clock>("/clock", 10)) {}

  // Publishes now, then advances in 1 ms steps to `until`, letting `o` spin in between.
  void run_to(NodeObserver& o, const ros::Time& until) {
    while (now_ < until && ros::ok()) {
      now_ += ros::Duration(0.001);
      publish();
      o.wait_until([] { return false; }, 0.001);
    }
  }
  void set(const ros::Time& t) {
    now_ = t;
    publish();
  }
  const ros::Time& now() const { return now_; }

 private:
  void publish() {
    rosgraph_msgs::Clock c;
    c.clock = now_;
    pub_.publish(c);
  }
  ros::Publisher pub_;
  ros::Time now_;
};

}  // namespace

TEST(StoneNodeSimTime, FollowsClockAtTheConfiguredRate) {
  NodeObserver o;
  ClockDriver clock;
  const ros::Time t_start(1000.0);
  // Until the node has seen the clock and published: the first /clock may be lost before the
  // node's subscription is connected, so keep publishing.
  clock.set(t_start);
  ASSERT_TRUE(o.wait_until(
      [&] {
        clock.run_to(o, clock.now() + ros::Duration(0.02));
        return o.info && !o.odom.empty();
      },
      30.0));
  const ros::Time t0 = o.info->header.stamp;
  EXPECT_GE(t0, t_start);
  EXPECT_LE(t0, clock.now());
  ASSERT_TRUE(o.wait_for_start());

  // Two simulated seconds; the rate is counted in simulated time, not wall time.
  const ros::Time window_start = clock.now() + ros::Duration(0.5);
  const ros::Time window_end = window_start + ros::Duration(1.0);
  clock.run_to(o, window_end + ros::Duration(0.5));
  o.wait_until([] { return false; }, 0.2);
  std::size_t in_window = 0;
  for (std::size_t i = 0; i < o.odom.size(); ++i) {
    const ros::Time& stamp = o.odom[i].header.stamp;
    EXPECT_LE(stamp, clock.now());
    EXPECT_EQ((stamp.toNSec() - t0.toNSec()) % o.info->dt_ns, 0u);
    if (i > 0) {
      EXPECT_GT(stamp, o.odom[i - 1].header.stamp);
    }
    if (stamp >= window_start && stamp < window_end) ++in_window;
  }
  // 50 Hz: one message per tick; a tick delayed past the next one merges with it.
  EXPECT_LE(in_window, 51u);
  EXPECT_GE(in_window, 40u);

  // tf on the simulated time line matches the closed form too.
  const vgtest::ClosedForm reference = vgtest::ClosedForm::from_info(*o.info);
  for (std::size_t i = o.odom.size() - 10; i < o.odom.size(); ++i) {
    const auto tf = o.tf_at(o.odom[i].header.stamp);
    ASSERT_TRUE(tf);
    const auto s = reference.at(vgtest::seconds_between(t0, tf->header.stamp));
    EXPECT_LT(vgtest::angle_between(s.orientation, vgtest::quat(tf->transform.rotation)), 1e-9);
  }

  // The clock jumps back by a second (a looping bag): a time_jump segment starts at the new
  // time and nothing from the old time line is published afterwards.
  const ros::Time before_jump = clock.now();
  const std::size_t seen_events = o.events.size(), seen_odom = o.odom.size();
  clock.set(before_jump - ros::Duration(1.0));
  const ros::Time jumped_to = clock.now();
  clock.run_to(o, jumped_to + ros::Duration(0.5));
  const auto event = o.wait_for_event(seen_events, 5.0);
  ASSERT_TRUE(event) << "no time_jump event";
  EXPECT_EQ(event->reason, "time_jump");
  EXPECT_GE(event->header.stamp, jumped_to);
  EXPECT_LE(event->header.stamp, jumped_to + ros::Duration(0.1));
  o.wait_until([] { return false; }, 0.2);
  // Messages in flight at the jump may still carry old stamps; after the first new-line stamp
  // every stamp is on the new line and increasing.
  std::size_t first_new = o.odom.size();
  for (std::size_t i = seen_odom; i < o.odom.size(); ++i) {
    if (o.odom[i].header.stamp < before_jump - ros::Duration(0.5)) {
      first_new = i;
      break;
    }
  }
  ASSERT_LT(first_new, o.odom.size()) << "nothing published after the jump";
  EXPECT_GE(o.odom.size() - first_new, 15u);
  for (std::size_t i = first_new; i < o.odom.size(); ++i) {
    EXPECT_GE(o.odom[i].header.stamp, jumped_to);
    EXPECT_LE(o.odom[i].header.stamp, clock.now());
    if (i > first_new) {
      EXPECT_GT(o.odom[i].header.stamp, o.odom[i - 1].header.stamp);
    }
  }
}
