// Test-side view of a running stone node: everything it publishes, collected by topic, plus a
// tf2 buffer. Callbacks run only inside wait_until (single-threaded spinOnce), so the tests
// read the vectors without locks; the tf listener has its own thread.
#pragma once

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry_msgs/PoseStamped.h"
#include "virtual_go/StoneEvent.h"
#include "virtual_go/StoneInfo.h"

namespace vgtest {

class NodeObserver {
 public:
  explicit NodeObserver(const std::string& node = "/stone")
      : node_(node), buffer_(ros::Duration(30.0)), listener_(buffer_) {
    ros::NodeHandle nh;
    subs_.push_back(nh.subscribe<nav_msgs::Odometry>(
        node + "/odom", 1000,
        [this](const nav_msgs::Odometry::ConstPtr& m) { odom.push_back(*m); }));
    subs_.push_back(nh.subscribe<geometry_msgs::PoseStamped>(
        node + "/pose", 1000,
        [this](const geometry_msgs::PoseStamped::ConstPtr& m) { pose.push_back(*m); }));
    subs_.push_back(nh.subscribe<virtual_go::StoneInfo>(
        node + "/info", 1, [this](const virtual_go::StoneInfo::ConstPtr& m) { info = *m; }));
    subs_.push_back(nh.subscribe<virtual_go::StoneEvent>(
        node + "/events", 100,
        [this](const virtual_go::StoneEvent::ConstPtr& m) { events.push_back(*m); }));
    subs_.push_back(nh.subscribe<visualization_msgs::Marker>(
        node + "/marker", 1, [this](const visualization_msgs::Marker::ConstPtr& m) {
          marker = *m;
          ++markers_received;
        }));
  }

  // Spins until pred() holds or the wall-clock timeout passes (sim time may stand still).
  bool wait_until(const std::function<bool()>& pred, double timeout_s = 20.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      ros::spinOnce();
      if (pred()) return true;
      ros::WallDuration(0.002).sleep();
    }
    ros::spinOnce();
    return pred();
  }

  // Waits for the latched topics and for tf; drops ~odom and ~pose messages that arrived
  // before the tf subscription was connected, so every kept stamp can be looked up.
  bool wait_for_start() {
    if (!wait_until([this] { return info && marker && !events.empty() && !odom.empty(); })) {
      return false;
    }
    std::optional<ros::Time> first_with_tf;
    const bool synced = wait_until([&] {
      for (const auto& m : odom) {
        if (buffer_.canTransform(info->world_frame, info->stone_frame, m.header.stamp)) {
          first_with_tf = m.header.stamp;
          return true;
        }
      }
      return false;
    });
    if (!synced) return false;
    const auto before = [&](const auto& m) { return m.header.stamp < *first_with_tf; };
    odom.erase(std::remove_if(odom.begin(), odom.end(), before), odom.end());
    pose.erase(std::remove_if(pose.begin(), pose.end(), before), pose.end());
    return true;
  }

  // Waits for the next event after `seen` events; returns it or nullopt.
  std::optional<virtual_go::StoneEvent> wait_for_event(std::size_t seen, double timeout_s = 10.0) {
    if (!wait_until([&] { return events.size() > seen; }, timeout_s)) return std::nullopt;
    return events[seen];
  }

  // Waits until `count` odom messages stamped after `after` have arrived; returns them.
  std::vector<nav_msgs::Odometry> odom_after(const ros::Time& after, std::size_t count,
                                             double timeout_s = 20.0) {
    std::vector<nav_msgs::Odometry> out;
    wait_until(
        [&] {
          out.clear();
          for (const auto& m : odom)
            if (m.header.stamp > after) out.push_back(m);
          return out.size() >= count;
        },
        timeout_s);
    return out;
  }

  // The world -> stone transform at exactly `stamp`, waiting (wall time) for it to arrive.
  std::optional<geometry_msgs::TransformStamped> tf_at(const ros::Time& stamp,
                                                       double timeout_s = 5.0) {
    const std::string world = info ? info->world_frame : "world";
    const std::string stone = info ? info->stone_frame : "stone";
    if (!wait_until([&] { return buffer_.canTransform(world, stone, stamp); }, timeout_s)) {
      return std::nullopt;
    }
    return buffer_.lookupTransform(world, stone, stamp);
  }

  // The latest world -> stone transform the listener holds, at its own stamp (not interpolated).
  std::optional<geometry_msgs::TransformStamped> latest_tf() {
    const std::string world = info ? info->world_frame : "world";
    const std::string stone = info ? info->stone_frame : "stone";
    if (!buffer_.canTransform(world, stone, ros::Time(0))) return std::nullopt;
    return buffer_.lookupTransform(world, stone, ros::Time(0));
  }

  template <class Service>
  bool call(const std::string& name, Service& service) {
    const std::string full = node_ + "/" + name;
    if (!ros::service::waitForService(full, ros::Duration(10.0))) return false;
    return ros::service::call(full, service);
  }

  std::vector<nav_msgs::Odometry> odom;
  std::vector<geometry_msgs::PoseStamped> pose;
  std::vector<virtual_go::StoneEvent> events;
  std::optional<virtual_go::StoneInfo> info;
  std::optional<visualization_msgs::Marker> marker;
  std::size_t markers_received = 0;

 private:
  std::string node_;
  std::vector<ros::Subscriber> subs_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
};

// Seconds from a to b, exactly from the integer nanoseconds.
inline double seconds_between(const ros::Time& a, const ros::Time& b) {
  return static_cast<double>(static_cast<std::int64_t>(b.toNSec()) -
                             static_cast<std::int64_t>(a.toNSec())) *
         1e-9;
}

}  // namespace vgtest
