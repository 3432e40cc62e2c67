// Small message builders shared by the tests that write bags with the rosbag C++ API
// (test_bags.cpp: synthetic flights; world_bags.cpp: the core's World on a grid).
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <ros/message_traits.h>
#include <ros/time.h>
#include <std_msgs/Header.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <boost/make_shared.hpp>
#include <boost/shared_ptr.hpp>
#include <cstdint>
#include <map>
#include <string>

namespace virtual_go_test {

inline ros::Time stamp(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

inline geometry_msgs::Vector3 vec_msg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

inline geometry_msgs::Pose pose_msg(const Eigen::Vector3d& x, const Eigen::Quaterniond& q) {
  geometry_msgs::Pose p;
  p.position.x = x.x();
  p.position.y = x.y();
  p.position.z = x.z();
  p.orientation.w = q.w();
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  return p;
}

// The node's one transform, header.frame_id (world) -> "stone".
inline tf2_msgs::TFMessage stone_tf_msg(const std_msgs::Header& header,
                                        const Eigen::Vector3d& position_world,
                                        const geometry_msgs::Quaternion& orientation) {
  geometry_msgs::TransformStamped transform;
  transform.header = header;
  transform.child_frame_id = "stone";
  transform.transform.translation = vec_msg(position_world);
  transform.transform.rotation = orientation;
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(transform);
  return tf;
}

// The connection header of a latched topic of the node. rosbag stores a given connection header
// as is, so it must carry the type fields too.
template <class M>
boost::shared_ptr<ros::M_string> latched_header() {
  auto h = boost::make_shared<ros::M_string>();
  (*h)["type"] = ros::message_traits::datatype<M>();
  (*h)["md5sum"] = ros::message_traits::md5sum<M>();
  (*h)["message_definition"] = ros::message_traits::definition<M>();
  (*h)["latching"] = "1";
  (*h)["callerid"] = "/stone";
  return h;
}

}  // namespace virtual_go_test
