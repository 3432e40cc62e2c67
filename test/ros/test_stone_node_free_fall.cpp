// The node without the board (test/ros/config/free_fall.yaml): a stone let go at rest at the
// world origin, no reset of either kind. An earlier node (5db2375) crashed in this scene on its
// first publish (publish_state asked a null World is_resting). For seconds of simulated time the
// node keeps publishing ~odom and /tf (a real tf2 listener), every pose finite with a unit
// quaternion, and the centre on the free-fall closed form z(t) = z0 - g t^2 / 2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/node_observer.h"
#include "support/node_reference.h"

using vgtest::ClosedForm;
using vgtest::NodeObserver;

namespace {

constexpr double kG = 9.80665;        // m/s^2, free_fall.yaml
constexpr double kWatchS = 3.0;       // s of simulated time watched
constexpr double kWallLimitS = 40.0;  // s of wall time allowed for it (a loaded machine)

bool finite(const geometry_msgs::Transform& t) {
  return std::isfinite(t.translation.x) && std::isfinite(t.translation.y) &&
         std::isfinite(t.translation.z) && std::isfinite(t.rotation.x) &&
         std::isfinite(t.rotation.y) && std::isfinite(t.rotation.z) && std::isfinite(t.rotation.w);
}

bool finite(const nav_msgs::Odometry& m) {
  const auto& p = m.pose.pose;
  const auto& v = m.twist.twist;
  for (double x : {p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
                   p.orientation.z, p.orientation.w, v.linear.x, v.linear.y, v.linear.z,
                   v.angular.x, v.angular.y, v.angular.z}) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

}  // namespace

TEST(StoneNodeFreeFall, KeepsPublishingTheFreeFallWithoutTheBoard) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start()) << "no info, marker, events or odom from /stone: did it crash?";
  // The scene as free_fall.yaml writes it, not as the node reports it.
  EXPECT_EQ(vgtest::vec(o.info->initial_pose.position), Eigen::Vector3d::Zero());
  EXPECT_EQ(vgtest::vec(o.info->initial_twist.linear), Eigen::Vector3d::Zero());
  EXPECT_EQ(vgtest::vec(o.info->gravity), Eigen::Vector3d(0.0, 0.0, -kG));
  EXPECT_DOUBLE_EQ(o.info->auto_reset_period, 0.0);
  ASSERT_EQ(o.events.front().reason, "start");
  const ros::Time t0 = o.events.front().header.stamp;

  // Seconds of simulated time, whatever the wall time they take on a loaded machine.
  const bool watched = o.wait_until(
      [&] {
        return !o.odom.empty() &&
               vgtest::seconds_between(t0, o.odom.back().header.stamp) >= kWatchS;
      },
      kWallLimitS);
  ASSERT_TRUE(watched) << "the node stopped publishing ~odom after "
                       << (o.odom.empty() ? 0.0
                                          : vgtest::seconds_between(t0, o.odom.back().header.stamp))
                       << " s of simulated time: did it crash?";
  const double eps = std::numeric_limits<double>::epsilon();
  // Still alive at the end: one more message, later still.
  const ros::Time last = o.odom.back().header.stamp;
  EXPECT_EQ(o.odom_after(last, 1, 10.0).size(), 1u) << "no ~odom after " << last;

  double worst_z_m = 0.0, worst_angle = 0.0, lowest_z_m = 0.0;
  std::size_t checked = 0;
  for (const nav_msgs::Odometry& m : o.odom) {
    if (m.header.stamp <= t0) continue;
    ASSERT_TRUE(finite(m)) << "~odom at " << m.header.stamp << " is not finite";
    // The stamp is the simulated instant of the state: on the dt grid from the start.
    ASSERT_EQ((m.header.stamp.toNSec() - t0.toNSec()) % o.info->dt_ns, 0u) << m.header.stamp;
    const auto tf = o.tf_at(m.header.stamp);
    ASSERT_TRUE(tf) << "no tf at " << m.header.stamp;
    ASSERT_TRUE(finite(tf->transform)) << "tf at " << m.header.stamp << " is not finite";
    const Eigen::Quaterniond q_tf = vgtest::quat(tf->transform.rotation);
    EXPECT_NEAR(q_tf.norm(), 1.0, 1e-12) << m.header.stamp;
    EXPECT_NEAR(vgtest::quat(m.pose.pose.orientation).norm(), 1.0, 1e-12) << m.header.stamp;
    const Eigen::Vector3d x_tf = vgtest::vec(tf->transform.translation);
    // tf2's lookup recomposes the transform: round-off only (relative: z reaches -44 m).
    EXPECT_LE((vgtest::vec(m.pose.pose.position) - x_tf).norm(), 4.0 * eps * x_tf.norm());

    // The motion restarts only at an event: with nothing to hit and no reset, none but a skip
    // ahead when a loaded machine leaves the physics behind ROS time (time_jump, which
    // continues from the state it had).
    const virtual_go::StoneEvent* segment = nullptr;
    for (const virtual_go::StoneEvent& e : o.events) {
      if (e.header.stamp > m.header.stamp) break;
      ASSERT_TRUE(e.reason == "start" || e.reason == "time_jump") << e.reason;
      segment = &e;
    }
    ASSERT_NE(segment, nullptr);
    const double t = vgtest::seconds_between(segment->header.stamp, m.header.stamp);
    const double z0 = segment->pose.position.z, vz0 = segment->twist.linear.z;
    const double z_ref = z0 + vz0 * t - 0.5 * kG * t * t;
    // Sampled at its stamp, the state is the closed form's at exactly that time (t is a whole
    // number of dt_ns in integer nanoseconds): timing adds nothing, only round-off, a few ulps
    // of each term (t, t^2 and the products, here and in the node). Read at its arrival instead,
    // a 10 ms delay would be g t 10 ms ~ 0.3 m at 3 s.
    const double tolerance = 16.0 * eps * (std::abs(z0) + std::abs(vz0 * t) + 0.5 * kG * t * t);
    EXPECT_NEAR(x_tf.z(), z_ref, tolerance) << "t = " << t << " s after " << segment->reason;
    // Nothing pushes it sideways: x and y stay those of the start.
    EXPECT_EQ(x_tf.x(), segment->pose.position.x);
    EXPECT_EQ(x_tf.y(), segment->pose.position.y);
    worst_z_m = std::max(worst_z_m, std::abs(x_tf.z() - z_ref));
    lowest_z_m = std::min(lowest_z_m, x_tf.z());
    // The orientation on the torque-free closed form (support/node_reference.h), the bound of
    // StoneNodeTf (the exact integrator's re-anchored round-off).
    const vgtest::MotionState s = ClosedForm::from_event(*o.info, *segment).at(t);
    worst_angle = std::max(worst_angle, vgtest::angle_between(s.orientation, q_tf));
    ++checked;
  }
  EXPECT_LT(worst_angle, 1e-9);
  // Fallen -g t^2 / 2 = -44 m in 3 s: far beyond any board, the motion watched all the way.
  EXPECT_LT(lowest_z_m, -0.5 * kG * kWatchS * kWatchS + 1.0);
  // 60 Hz over 3 s, fewer only if ticks were skipped under load.
  EXPECT_GT(checked, 30u);
  std::printf(
      "[ free fall ] %zu stamps over %.3f s, to z = %.3f m, worst |z - z_ref| %.3g m, "
      "worst angle %.3g rad\n",
      checked, vgtest::seconds_between(t0, last), lowest_z_m, worst_z_m, worst_angle);
}
