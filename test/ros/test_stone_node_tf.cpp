// The node against the closed form: tf looked up at received stamps, ~pose and ~odom agreeing
// with tf, the latched topics. Runs against a node with the exact integrator and no resets.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "support/node_observer.h"
#include "support/node_reference.h"

using vgtest::ClosedForm;
using vgtest::NodeObserver;

TEST(StoneNodeTf, LatchedTopicsArrive) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start()) << "no info, marker, events or odom from /stone";
  const virtual_go::StoneInfo& info = *o.info;
  EXPECT_EQ(info.world_frame, "world");
  EXPECT_EQ(info.stone_frame, "stone");
  EXPECT_EQ(info.integrator, "exact");
  EXPECT_EQ(info.dt_ns, 1000000);
  EXPECT_DOUBLE_EQ(info.dt, 0.001);
  EXPECT_DOUBLE_EQ(info.width, 0.022);
  EXPECT_DOUBLE_EQ(info.height, 0.0092);  // size 33
  EXPECT_GT(info.mass, 0.004);
  EXPECT_LT(info.mass, 0.006);
  EXPECT_EQ(info.principal_moments.x, info.principal_moments.y);
  EXPECT_GT(info.principal_moments.z, info.principal_moments.x);  // flat lens: I3 > I1
  EXPECT_GT(info.header.stamp.toNSec(), 0u);

  // ~info against values written here from test/ros/config/spin*.yaml and docs/physics.md, not from
  // the node's own output: ClosedForm::from_info trusts ~info, so a swapped x y z w / w x y z or an
  // ignored parameter would otherwise go unnoticed.
  // The .test file tells which model its YAML sets (spin.yaml: rigid_body,
  // spin_constant_omega.yaml: constant_omega); the rest of the YAML is the same.
  std::string expected_model;
  ASSERT_TRUE(ros::param::get("~expected_model", expected_model)) << "set in the .test file";
  EXPECT_EQ(info.model, expected_model);
  EXPECT_DOUBLE_EQ(info.rate, 50.0);
  EXPECT_DOUBLE_EQ(info.auto_reset_period, 0.0);
  EXPECT_DOUBLE_EQ(info.max_angular_velocity, 500.0);  // the default
  EXPECT_EQ(vgtest::vec(info.gravity), Eigen::Vector3d(0.0, 0.0, -9.80665));
  EXPECT_EQ(vgtest::vec(info.initial_pose.position), Eigen::Vector3d(0.01, -0.02, 0.5));
  // The YAML quaternion is x y z w, 30 degrees about x, normalised by the node (|q| is 1 to 5e-8).
  const geometry_msgs::Quaternion& q = info.initial_pose.orientation;
  EXPECT_NEAR(q.x, 0.2588190, 1e-7);
  EXPECT_NEAR(q.y, 0.0, 1e-15);
  EXPECT_NEAR(q.z, 0.0, 1e-15);
  EXPECT_NEAR(q.w, 0.9659258, 1e-7);
  EXPECT_LT((vgtest::vec(info.initial_twist.linear) - Eigen::Vector3d(0.1, 0.05, 1.0)).norm(),
            1e-15);
  // Round trip w -> L = R I R^T w -> w costs a few ulps.
  EXPECT_LT((vgtest::vec(info.initial_twist.angular) - Eigen::Vector3d(7.0, -3.0, 45.0)).norm(),
            1e-12);
  // Size 33 slate lens (docs/physics.md, "The lens"): a = w / 2, c = h / 2, rho 2700 kg/m^3.
  const double a = 0.011, c = 0.0046, rho = 2700.0, a2 = a * a, c2 = c * c;
  const double i3 = M_PI * rho * c * (10 * a2 * a2 + 5 * a2 * c2 + c2 * c2) / 30;
  const double i1 = M_PI * rho * c * (10 * a2 * a2 + 15 * a2 * c2 + 7 * c2 * c2) / 60;
  const double mass = rho * M_PI * c * (3 * a2 + c2) / 3;
  EXPECT_DOUBLE_EQ(info.density, rho);
  EXPECT_NEAR(info.mass / mass, 1.0, 1e-12);
  EXPECT_NEAR(info.principal_moments.x / i1, 1.0, 1e-12);
  EXPECT_NEAR(info.principal_moments.y / i1, 1.0, 1e-12);
  EXPECT_NEAR(info.principal_moments.z / i3, 1.0, 1e-12);

  // ~marker: a MESH_RESOURCE naming a binary STL of this stone (22 x 9.2 mm) that exists.
  const visualization_msgs::Marker& marker = *o.marker;
  EXPECT_EQ(marker.type, visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_EQ(marker.header.frame_id, "stone");
  EXPECT_TRUE(marker.frame_locked);
  EXPECT_TRUE(marker.points.empty());
  ASSERT_EQ(marker.mesh_resource.rfind("file:///", 0), 0u) << marker.mesh_resource;
  std::ifstream mesh(marker.mesh_resource.substr(7), std::ios::binary);
  ASSERT_TRUE(mesh) << marker.mesh_resource;
  const std::string stl((std::istreambuf_iterator<char>(mesh)), std::istreambuf_iterator<char>());
  ASSERT_GE(stl.size(), 84u);
  std::uint32_t facets = 0;
  std::memcpy(&facets, stl.data() + 80, 4);  // little-endian, as this (x86) machine
  EXPECT_GT(facets, 100u);
  ASSERT_EQ(stl.size(), 84u + 50u * facets);
  for (std::uint32_t t = 0; t < facets; ++t) {
    for (int v = 1; v <= 3; ++v) {
      float p[3];
      std::memcpy(p, stl.data() + 84 + 50 * t + 12 * v, sizeof p);
      EXPECT_LE(std::hypot(p[0], p[1]), 0.011 + 1e-8);
      EXPECT_LE(std::abs(p[2]), 0.0046 + 1e-8);
    }
  }
  // Republished every second, so a viewer that dropped one gets the next.
  const std::size_t seen = o.markers_received;
  EXPECT_TRUE(o.wait_until([&] { return o.markers_received >= seen + 2; }, 4.0))
      << "~marker not republished";

  const virtual_go::StoneEvent& start = o.events.front();
  EXPECT_EQ(start.segment, 0u);
  EXPECT_EQ(start.reason, "start");
  EXPECT_EQ(start.header.stamp, info.header.stamp);
  EXPECT_EQ(start.pose, info.initial_pose);
  EXPECT_EQ(o.events.size(), 1u) << "no reset configured, yet more than one segment";
}

TEST(StoneNodeTf, TfAtReceivedStampsMatchesTheClosedForm) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  const ClosedForm reference = ClosedForm::from_info(*o.info);
  const ros::Time t0 = o.info->header.stamp;
  const auto odom = o.odom_after(t0, 40);
  ASSERT_GE(odom.size(), 40u);

  double worst_angle = 0.0, worst_position = 0.0;
  for (const auto& m : odom) {
    const auto tf = o.tf_at(m.header.stamp);
    ASSERT_TRUE(tf) << "no tf at " << m.header.stamp;
    ASSERT_EQ(tf->header.stamp, m.header.stamp);
    const vgtest::MotionState s = reference.at(vgtest::seconds_between(t0, m.header.stamp));
    const Eigen::Quaterniond q_tf = vgtest::quat(tf->transform.rotation);
    const Eigen::Vector3d x_tf = vgtest::vec(tf->transform.translation);
    EXPECT_NEAR(q_tf.norm(), 1.0, 1e-12);
    worst_angle = std::max(worst_angle, vgtest::angle_between(s.orientation, q_tf));
    worst_position = std::max(worst_position, (s.position - x_tf).norm());

    // ~odom: pose equals tf; twist in the stone frame (R^T v, R^T w).
    EXPECT_EQ(m.header.frame_id, "world");
    EXPECT_EQ(m.child_frame_id, "stone");
    // tf2's lookup recomposes the transform, so allow for round-off only.
    EXPECT_LT((vgtest::vec(m.pose.pose.position) - x_tf).norm(), 1e-15);
    EXPECT_LT(vgtest::angle_between(vgtest::quat(m.pose.pose.orientation), q_tf), 1e-12);
    const Eigen::Matrix3d r_t = q_tf.toRotationMatrix().transpose();
    EXPECT_LT((vgtest::vec(m.twist.twist.linear) - r_t * s.velocity).norm(), 1e-9);
    EXPECT_LT((vgtest::vec(m.twist.twist.angular) - r_t * s.angular_velocity_world).norm(), 1e-8);
  }
  EXPECT_LT(worst_angle, 1e-9);
  EXPECT_LT(worst_position, 1e-9);

  // ~pose: same stamps as tf, same pose.
  std::size_t matched = 0;
  for (const auto& p : o.pose) {
    if (p.header.stamp <= t0) continue;
    const auto tf = o.tf_at(p.header.stamp);
    ASSERT_TRUE(tf);
    EXPECT_EQ(p.header.frame_id, "world");
    EXPECT_LT((vgtest::vec(p.pose.position) - vgtest::vec(tf->transform.translation)).norm(),
              1e-15);
    EXPECT_LT(vgtest::angle_between(vgtest::quat(p.pose.orientation),
                                    vgtest::quat(tf->transform.rotation)),
              1e-12);
    ++matched;
  }
  EXPECT_GT(matched, 20u);
}

TEST(StoneNodeTf, StampsStrictlyIncreaseOnTheDtGrid) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  const ros::Time t0 = o.info->header.stamp;
  const auto odom = o.odom_after(t0, 30);
  ASSERT_GE(odom.size(), 30u);
  for (std::size_t i = 0; i < odom.size(); ++i) {
    EXPECT_EQ((odom[i].header.stamp.toNSec() - t0.toNSec()) % o.info->dt_ns, 0u);
    if (i > 0) {
      EXPECT_GT(odom[i].header.stamp, odom[i - 1].header.stamp);
    }
  }
  for (std::size_t i = 1; i < o.pose.size(); ++i) {
    EXPECT_GT(o.pose[i].header.stamp, o.pose[i - 1].header.stamp);
  }
}
