#include "support/test_bags.h"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>
#include <topic_tools/shape_shifter.h>
#include <virtual_go/StoneEvent.h>
#include <virtual_go/StoneInfo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "support/bag_messages.h"

namespace virtual_go_test {
namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.80665);
const Eigen::Vector3d kX0(0.1, -0.2, 0.5);
const Eigen::Vector3d kV0(0.3, 0.1, 2.0);
// Tilted 30 degrees about x; spin mostly about the symmetry axis with a wobble.
const Eigen::Quaterniond kQ0(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX()));
const Eigen::Vector3d kOmegaBody0(4.0, -3.0, 25.0);

// The StoneEvent before it named its stone: the fields of today's message but the two names at
// its end, as an old stone_node recorded it.
topic_tools::ShapeShifter event_before_stone_names(const virtual_go::StoneEvent& event) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(event));
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(out, event);
  bytes.resize(bytes.size() - 8);  // two empty strings: their lengths of 0
  std::istringstream in(ros::message_traits::definition<virtual_go::StoneEvent>());
  std::string definition, line;
  while (std::getline(in, line)) {
    if (line.rfind("string stone", 0) != 0 && line.rfind("string other_stone", 0) != 0) {
      definition += line + "\n";
    }
  }
  topic_tools::ShapeShifter shifter;
  shifter.morph("297586e22de15a89da82e4c718f1324f", "virtual_go/StoneEvent", definition, "1");
  ros::serialization::IStream read(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  shifter.read(read);
  return shifter;
}

}  // namespace

TrueState true_state(double t) {
  // L is fixed in the world; the body spins about e_z at -Omega relative to the frame that
  // rotates about L at |L| / I1 (Euler's solution for I1 = I2).
  const Eigen::Vector3d l_body0(kI1 * kOmegaBody0.x(), kI1 * kOmegaBody0.y(),
                                kI3 * kOmegaBody0.z());
  const Eigen::Vector3d l_world = kQ0 * l_body0;
  const double big_omega = (kI3 - kI1) * kOmegaBody0.z() / kI1;
  const Eigen::Quaterniond left(Eigen::AngleAxisd(t * l_world.norm() / kI1, l_world.normalized()));
  const Eigen::Quaterniond right(Eigen::AngleAxisd(-big_omega * t, Eigen::Vector3d::UnitZ()));
  TrueState s;
  s.orientation = (left * kQ0 * right).normalized();
  s.position = kX0 + kV0 * t + 0.5 * t * t * kGravity;
  s.velocity_world = kV0 + t * kGravity;
  s.angular_momentum_world = l_world;
  const Eigen::Vector3d l_body = s.orientation.conjugate() * l_world;
  s.angular_velocity_body = Eigen::Vector3d(l_body.x() / kI1, l_body.y() / kI1, l_body.z() / kI3);
  return s;
}

std::size_t write_run_bag(const std::string& path, const SyntheticRun& run) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  const ros::Time start = stamp(run.start_ns);

  if (run.with_info) {
    virtual_go::StoneInfo info;
    info.header.stamp = start;
    info.header.frame_id = "world";
    info.world_frame = "world";
    info.stone_frame = "stone";
    info.width = 0.022;
    info.height = 0.009;
    info.mass = kMass;
    info.density = 2700.0;
    info.principal_moments = vec_msg({kI1, kI1, kI3});
    info.model = run.model;
    info.integrator = run.integrator;
    info.dt = 0.001;
    info.dt_ns = 1000000;
    info.rate = run.rate;
    info.gravity = vec_msg(kGravity);
    const TrueState s0 = true_state(0.0);
    info.initial_pose = pose_msg(s0.position, s0.orientation);
    bag.write("/stone/info", start, info, latched_header<virtual_go::StoneInfo>());
  }
  auto write_event = [&](std::int64_t ns, std::uint32_t segment, const std::string& reason,
                         double huge = 0.0) {
    const TrueState s0 = true_state(0.0);
    virtual_go::StoneEvent e;
    e.header.stamp = stamp(ns);
    e.header.frame_id = "world";
    e.segment = segment;
    e.reason = reason;
    e.pose = pose_msg(s0.position, s0.orientation);
    e.twist.linear = vec_msg(s0.velocity_world);
    if (huge != 0.0) {
      e.pose.position.x = huge;
      e.twist.linear.x = huge;
    }
    e.twist.angular = vec_msg(s0.orientation * s0.angular_velocity_body);
    e.angular_momentum = vec_msg(s0.angular_momentum_world);
    if (run.events_before_stone_names) {
      const topic_tools::ShapeShifter old = event_before_stone_names(e);
      auto header = latched_header<virtual_go::StoneEvent>();
      (*header)["md5sum"] = old.getMD5Sum();
      (*header)["message_definition"] = old.getMessageDefinition();
      bag.write("/stone/events", stamp(ns), old, header);
      return;
    }
    e.stone = "stone";
    bag.write("/stone/events", stamp(ns), e, latched_header<virtual_go::StoneEvent>());
  };
  if (run.with_events) write_event(run.start_ns, 0, "start");

  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / run.rate));
  const auto count = static_cast<std::size_t>(std::llround(run.duration * run.rate)) + 1;
  const auto reset_ns = static_cast<std::int64_t>(std::llround(run.reset_after * 1e9));
  const auto overflow_ns =
      static_cast<std::int64_t>(std::llround(run.overflowing_event_after * 1e9));
  bool reset_written = false, overflow_written = false;
  std::size_t written = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (std::count(run.drop.begin(), run.drop.end(), i) > 0) continue;
    const std::int64_t since_start = static_cast<std::int64_t>(i) * period_ns;
    // After a reset the motion starts again from the initial state at the reset time.
    std::int64_t segment_start = 0;
    if (overflow_ns > 0 && since_start >= overflow_ns && !overflow_written) {
      write_event(run.start_ns + overflow_ns, 1, "set_state", 1.5e308);
      overflow_written = true;
    }
    if (reset_ns > 0 && since_start >= reset_ns) {
      segment_start = reset_ns;
      if (!reset_written && run.with_events && !run.reset_without_event) {
        write_event(run.start_ns + reset_ns, overflow_written ? 2 : 1, run.reset_reason);
      }
      reset_written = true;
    }
    const double t = static_cast<double>(since_start - segment_start) * 1e-9;
    TrueState s = true_state(t);
    if (run.orientation_drift_rate != 0.0) {
      s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(run.orientation_drift_rate * t,
                                                           Eigen::Vector3d::UnitZ())) *
                      s.orientation;
    }
    const ros::Time when = stamp(run.start_ns + since_start);

    nav_msgs::Odometry odom;
    odom.header.stamp = when;
    odom.header.frame_id = "world";
    odom.child_frame_id = "stone";
    odom.pose.pose = pose_msg(s.position, s.orientation);
    odom.twist.twist.linear = vec_msg(s.orientation.conjugate() * s.velocity_world);
    odom.twist.twist.angular = vec_msg(s.angular_velocity_body);
    if (std::count(run.nan_odom.begin(), run.nan_odom.end(), i) > 0) {
      odom.pose.pose.position.x = std::numeric_limits<double>::quiet_NaN();
    }
    geometry_msgs::PoseStamped pose;
    pose.header = odom.header;
    pose.pose = odom.pose.pose;
    const tf2_msgs::TFMessage tf =
        stone_tf_msg(odom.header, s.position, odom.pose.pose.orientation);

    const int copies = std::count(run.duplicate.begin(), run.duplicate.end(), i) > 0 ? 2 : 1;
    for (int c = 0; c < copies; ++c) {
      bag.write("/stone/odom", when, odom);
      bag.write("/stone/pose", when, pose);
      if (run.with_tf) bag.write("/tf", when, tf);
      ++written;
    }
  }
  bag.close();
  return written;
}

void write_empty_bag(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.close();
}

}  // namespace virtual_go_test
