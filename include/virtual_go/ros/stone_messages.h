// Core state -> ROS messages (REP 103 units). Conversions of Eigen types go through tf2_eigen.
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <visualization_msgs/Marker.h>

#include <cstdint>

#include "virtual_go/StoneEvent.h"
#include "virtual_go/StoneInfo.h"
#include "virtual_go/StoneStates.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/geometry/tessellation.h"
#include "virtual_go/sim/segment_event.h"
#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/stone_states.h"

namespace virtual_go {

ros::Time to_ros_time(std::int64_t ns);

// Messages of a StateOutput (sim/state_output.h): the numbers the simulation checked finite,
// copied, so the node publishes nothing it did not check.
geometry_msgs::Pose to_pose_msg(const StateOutput& output);
// World-frame twist: linear m/s, angular rad/s.
geometry_msgs::Twist to_world_twist_msg(const StateOutput& output);
// Body-frame twist (the nav_msgs/Odometry convention): R^T v and the body angular velocity.
geometry_msgs::Twist to_body_twist_msg(const StateOutput& output);

geometry_msgs::TransformStamped to_transform_msg(const StateOutput& output, const ros::Time& stamp,
                                                 const std::string& world_frame,
                                                 const std::string& stone_frame);
geometry_msgs::PoseStamped to_pose_stamped_msg(const StateOutput& output, const ros::Time& stamp,
                                               const std::string& world_frame);
nav_msgs::Odometry to_odometry_msg(const StateOutput& output, const ros::Time& stamp,
                                   const std::string& world_frame, const std::string& stone_frame);

StoneInfo to_info_msg(const StoneSimulation& sim);
StoneEvent to_event_msg(const SegmentEvent& event, const std::string& world_frame);
// ~stones: the entries (sim/stone_states.h) copied into parallel arrays, entry i at index i.
StoneStates to_stone_states_msg(const std::vector<StoneStateEntry>& stones, const ros::Time& stamp,
                                const std::string& world_frame);
// The lens as rviz draws it (body frame), for both marker forms below.
TriangleMesh stone_display_mesh(const Stone& stone);
// The tessellated lens as a TRIANGLE_LIST in the stone frame, locked to it so rviz moves it
// with tf. 138 KB: the fallback when the mesh file cannot be written.
visualization_msgs::Marker to_marker_msg(const Stone& stone, const std::string& color,
                                         const std::string& stone_frame);
// The same lens as a MESH_RESOURCE marker naming a mesh file (file:// URI), a few hundred
// bytes, so it can be republished.
visualization_msgs::Marker to_mesh_marker_msg(const std::string& mesh_uri, const std::string& color,
                                              const std::string& stone_frame);

}  // namespace virtual_go
