// ~stones (virtual_go/StoneStates) with a real master (test/ros/config/stones_drop.yaml): a
// white stone named white_stone dropped near D16. Each ~stones message is held to what the node
// publishes elsewhere: the pose bit for bit that of ~odom at the same stamp (and /tf's up to
// tf2's round-off), the world twist ~odom's body twist rotated into the world, width, height and
// mass ~info's. While the stone moves, one message per published state; at rest, the latched
// message says so, and a subscriber that comes late gets it.
#include <gtest/gtest.h>
#include <std_srvs/Trigger.h>

#include <map>
#include <string>
#include <vector>

#include "support/node_observer.h"
#include "support/node_reference.h"
#include "virtual_go/StoneStates.h"

using vgtest::NodeObserver;

namespace {

std::uint64_t ns(const ros::Time& t) { return t.toNSec(); }

bool same_pose(const geometry_msgs::Pose& a, const geometry_msgs::Pose& b) {
  return a.position.x == b.position.x && a.position.y == b.position.y &&
         a.position.z == b.position.z && a.orientation.x == b.orientation.x &&
         a.orientation.y == b.orientation.y && a.orientation.z == b.orientation.z &&
         a.orientation.w == b.orientation.w;
}

}  // namespace

TEST(StoneNodeStones, EveryEntryAgreesWithOdomTfAndInfo) {
  NodeObserver o;
  std::vector<virtual_go::StoneStates> stones;
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe<virtual_go::StoneStates>(
      "/stone/stones", 1000,
      [&](const virtual_go::StoneStates::ConstPtr& m) { stones.push_back(*m); });
  ASSERT_TRUE(o.wait_for_start()) << "no info, marker, events or odom from /stone";
  const virtual_go::StoneInfo& info = *o.info;
  ASSERT_EQ(info.stone_frame, "white_stone");

  // Drop again from the start, with both subscriptions in place, and follow it to rest.
  const auto rest_after = [&](std::size_t from) {
    for (std::size_t i = from; i < o.events.size(); ++i) {
      if (o.events[i].reason == "rest") return i;
    }
    return o.events.size();
  };
  ASSERT_TRUE(o.wait_until([&] { return rest_after(0) < o.events.size(); }, 30.0))
      << "no rest event";
  const std::size_t seen = o.events.size();
  std_srvs::Trigger reset;
  ASSERT_TRUE(o.call("reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  ASSERT_TRUE(o.wait_until([&] { return rest_after(seen) < o.events.size(); }, 30.0))
      << "no rest after the reset";
  const virtual_go::StoneEvent rest = o.events[rest_after(seen)];
  const virtual_go::StoneEvent start = o.events[seen + 1];  // after the wake
  ASSERT_EQ(start.reason, "reset");
  EXPECT_EQ(start.stone, "white_stone");
  EXPECT_EQ(rest.stone, "white_stone");
  // Half a second more: nothing moves, so nothing but the rest goes out.
  o.odom_after(rest.header.stamp, 100, 20.0);
  o.wait_until([] { return false; }, 0.5);

  std::map<std::uint64_t, nav_msgs::Odometry> odom_at;
  for (const nav_msgs::Odometry& m : o.odom) odom_at[ns(m.header.stamp)] = m;
  // The rest's instant is its stamp plus a sub-ns offset: a tick at that stamp comes before it
  // unless the offset is 0.
  const auto at_rest = [&](const ros::Time& t) {
    return t > rest.header.stamp || (t == rest.header.stamp && rest.time_offset == 0.0);
  };
  std::size_t moving = 0, compared = 0, resting = 0;
  for (const virtual_go::StoneStates& s : stones) {
    const ros::Time stamp = s.header.stamp;
    if (stamp < start.header.stamp) continue;
    ASSERT_EQ(s.name.size(), 1u);
    ASSERT_EQ(s.color.size(), 1u);
    ASSERT_EQ(s.point.size(), 1u);
    ASSERT_EQ(s.width.size(), 1u);
    ASSERT_EQ(s.height.size(), 1u);
    ASSERT_EQ(s.mass.size(), 1u);
    ASSERT_EQ(s.pose.size(), 1u);
    ASSERT_EQ(s.twist.size(), 1u);
    ASSERT_EQ(s.resting.size(), 1u);
    EXPECT_EQ(s.header.frame_id, info.world_frame);
    EXPECT_EQ(s.name[0], "white_stone");
    EXPECT_EQ(s.color[0], "white");
    // Falling, bouncing and resting, the centre stays within 4.2 mm of D16's vertical.
    EXPECT_EQ(s.point[0], "D16");
    EXPECT_EQ(s.width[0], info.width);
    EXPECT_EQ(s.height[0], info.height);
    EXPECT_EQ(s.mass[0], info.mass);
    ++(s.resting[0] ? resting : moving);
    EXPECT_EQ(s.resting[0], at_rest(stamp)) << stamp;
    const auto it = odom_at.find(ns(stamp));
    if (it == odom_at.end()) continue;
    ++compared;
    const nav_msgs::Odometry& odom = it->second;
    EXPECT_TRUE(same_pose(s.pose[0], odom.pose.pose)) << stamp;
    const Eigen::Quaterniond q = vgtest::quat(odom.pose.pose.orientation);
    const Eigen::Vector3d v_world = q * vgtest::vec(odom.twist.twist.linear);
    const Eigen::Vector3d w_world = q * vgtest::vec(odom.twist.twist.angular);
    EXPECT_LE((vgtest::vec(s.twist[0].linear) - v_world).norm(), 1e-14 * v_world.norm());
    EXPECT_LE((vgtest::vec(s.twist[0].angular) - w_world).norm(), 1e-14 * w_world.norm());
    if (s.resting[0]) {
      EXPECT_EQ(vgtest::vec(s.twist[0].linear), Eigen::Vector3d::Zero());
      EXPECT_EQ(vgtest::vec(s.twist[0].angular), Eigen::Vector3d::Zero());
    }
    const auto tf = o.tf_at(stamp);
    ASSERT_TRUE(tf) << "no tf at " << stamp;
    // tf2's lookup recomposes the transform, so allow for round-off only (as stone_node_tf).
    EXPECT_LT((vgtest::vec(tf->transform.translation) - vgtest::vec(s.pose[0].position)).norm(),
              1e-15);
    EXPECT_LT(vgtest::angle_between(vgtest::quat(tf->transform.rotation),
                                    vgtest::quat(s.pose[0].orientation)),
              1e-12);
  }
  // One message per published state from the reset to the rest (subscribed, moving).
  std::size_t odom_in_motion = 0;
  for (const nav_msgs::Odometry& m : o.odom) {
    odom_in_motion += m.header.stamp >= start.header.stamp && !at_rest(m.header.stamp);
  }
  EXPECT_GT(odom_in_motion, 20u);
  EXPECT_EQ(moving, odom_in_motion);
  // At rest nothing changes: one message, at the rest's tick, and none in the half second after.
  EXPECT_EQ(resting, 1u);
  EXPECT_EQ(compared, moving + resting);

  // A late subscriber gets the latched rest.
  std::optional<virtual_go::StoneStates> late;
  ros::Subscriber late_sub = nh.subscribe<virtual_go::StoneStates>(
      "/stone/stones", 1, [&](const virtual_go::StoneStates::ConstPtr& m) { late = *m; });
  ASSERT_TRUE(o.wait_until([&] { return late.has_value(); }, 10.0));
  ASSERT_EQ(late->resting.size(), 1u);
  EXPECT_TRUE(late->resting[0]);
  EXPECT_TRUE(same_pose(late->pose[0], rest.pose));
}
