#include "virtual_go/ros/stone_messages.h"

#include <tf2_eigen/tf2_eigen.h>

#include "virtual_go/geometry/tessellation.h"

namespace virtual_go {
namespace {

geometry_msgs::Vector3 to_vector_msg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 msg;
  tf2::toMsg(v, msg);
  return msg;
}

geometry_msgs::Twist to_twist_msg(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  geometry_msgs::Twist msg;
  msg.linear = to_vector_msg(linear);
  msg.angular = to_vector_msg(angular);
  return msg;
}

}  // namespace

ros::Time to_ros_time(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

geometry_msgs::Pose to_pose_msg(const StateOutput& output) {
  // Position and quaternion directly (not via a rotation matrix) so nothing is rounded twice.
  geometry_msgs::Pose msg;
  msg.position = tf2::toMsg(output.position_world);
  msg.orientation = tf2::toMsg(output.orientation);
  return msg;
}

geometry_msgs::Twist to_world_twist_msg(const StateOutput& output) {
  return to_twist_msg(output.velocity_world, output.angular_velocity_world);
}

geometry_msgs::Twist to_body_twist_msg(const StateOutput& output) {
  return to_twist_msg(output.velocity_body, output.angular_velocity_body);
}

geometry_msgs::TransformStamped to_transform_msg(const StateOutput& output, const ros::Time& stamp,
                                                 const std::string& world_frame,
                                                 const std::string& stone_frame) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = world_frame;
  msg.child_frame_id = stone_frame;
  tf2::toMsg(output.position_world, msg.transform.translation);
  msg.transform.rotation = tf2::toMsg(output.orientation);
  return msg;
}

geometry_msgs::PoseStamped to_pose_stamped_msg(const StateOutput& output, const ros::Time& stamp,
                                               const std::string& world_frame) {
  geometry_msgs::PoseStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = world_frame;
  msg.pose = to_pose_msg(output);
  return msg;
}

nav_msgs::Odometry to_odometry_msg(const StateOutput& output, const ros::Time& stamp,
                                   const std::string& world_frame, const std::string& stone_frame) {
  nav_msgs::Odometry msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = world_frame;
  msg.child_frame_id = stone_frame;
  msg.pose.pose = to_pose_msg(output);
  msg.twist.twist = to_body_twist_msg(output);
  // Covariances stay zero: the simulated state is known exactly.
  return msg;
}

StoneInfo to_info_msg(const StoneSimulation& sim) {
  const StoneConfig& c = sim.config();
  const Stone& stone = sim.stone();
  StoneInfo msg;
  msg.header.stamp = to_ros_time(sim.start_ns());
  msg.header.frame_id = c.world_frame;
  msg.world_frame = c.world_frame;
  msg.stone_frame = c.stone_frame;
  msg.width = stone.shape.width();
  msg.height = stone.shape.height();
  msg.mass = stone.mass_properties.mass();
  msg.density = stone.density;
  msg.principal_moments = to_vector_msg(stone.mass_properties.principal_moments_body());
  msg.model = motion_model_name(sim.setup().model.kind());
  msg.integrator = sim.integrator().name();
  msg.dt_ns = sim.dt_ns();
  msg.dt = sim.dt_s();
  msg.rate = c.rate_hz;
  msg.gravity = to_vector_msg(sim.setup().gravity_world);
  const StateOutput initial = state_output(sim.setup().model, sim.initial_state());
  msg.initial_pose = to_pose_msg(initial);
  msg.initial_twist = to_world_twist_msg(initial);
  msg.max_angular_velocity = c.max_angular_velocity;
  msg.auto_reset_period = c.auto_reset_period_s;
  // The board and materials as the simulation uses them (the parameters, checked).
  msg.board_enabled = c.board_enabled;
  msg.board_size = to_vector_msg(c.board_size_m);
  msg.board_restitution = c.board_material.restitution;
  msg.board_friction = c.board_material.friction;
  msg.board_rolling_resistance = c.board_material.rolling_resistance_m;
  msg.board_spinning_friction = c.board_material.spinning_friction_m;
  msg.table_restitution = c.table_material.restitution;
  msg.table_friction = c.table_material.friction;
  msg.table_rolling_resistance = c.table_material.rolling_resistance_m;
  msg.table_spinning_friction = c.table_material.spinning_friction_m;
  msg.zeno_height = c.zeno_height_m;
  msg.auto_reset_after_rest = c.auto_reset_after_rest_s;
  return msg;
}

StoneEvent to_event_msg(const SegmentEvent& event, const std::string& world_frame) {
  StoneEvent msg;
  msg.header.stamp = to_ros_time(event.stamp_ns);
  msg.header.frame_id = world_frame;
  msg.time_offset = event.time_offset_s;
  msg.segment = event.segment;
  msg.reason = event_reason_name(event.reason);
  msg.detail = event.detail;
  msg.stone = event.stone;
  msg.other_stone = event.other_stone;
  msg.pose = to_pose_msg(event.output);
  msg.twist = to_world_twist_msg(event.output);
  msg.angular_momentum = to_vector_msg(event.output.angular_momentum_world);
  return msg;
}

StoneStates to_stone_states_msg(const std::vector<StoneStateEntry>& stones, const ros::Time& stamp,
                                const std::string& world_frame) {
  StoneStates msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = world_frame;
  for (const StoneStateEntry& s : stones) {
    msg.name.push_back(s.name);
    msg.color.push_back(s.color);
    msg.point.push_back(s.point);
    msg.width.push_back(s.width_m);
    msg.height.push_back(s.height_m);
    msg.mass.push_back(s.mass_kg);
    msg.pose.push_back(to_pose_msg(s.output));
    msg.twist.push_back(to_world_twist_msg(s.output));
    msg.resting.push_back(s.resting);
  }
  return msg;
}

namespace {

// The marker fields both forms share: frame-locked to the stone frame, stamp zero (rviz then
// draws it at the latest transform of that frame), the stone's colour.
visualization_msgs::Marker stone_marker_base(const std::string& color,
                                             const std::string& stone_frame) {
  visualization_msgs::Marker msg;
  msg.header.frame_id = stone_frame;
  msg.header.stamp = ros::Time();  // zero: rviz uses the latest transform of the stone frame
  msg.frame_locked = true;
  msg.ns = "stone";
  msg.id = 0;
  msg.action = visualization_msgs::Marker::ADD;
  msg.pose.orientation.w = 1.0;
  msg.scale.x = msg.scale.y = msg.scale.z = 1.0;
  // Slate black and shell white, slightly off the extremes so rviz shading stays visible.
  const bool black = color == "black";
  msg.color.r = black ? 0.06f : 0.93f;
  msg.color.g = black ? 0.06f : 0.93f;
  msg.color.b = black ? 0.07f : 0.90f;
  msg.color.a = 1.0f;
  return msg;
}

}  // namespace

TriangleMesh stone_display_mesh(const Stone& stone) {
  // Fine enough that the silhouette looks round at the default camera distance.
  return tessellate_lens(stone.shape, 64, 8);
}

visualization_msgs::Marker to_marker_msg(const Stone& stone, const std::string& color,
                                         const std::string& stone_frame) {
  const TriangleMesh mesh = stone_display_mesh(stone);
  visualization_msgs::Marker msg = stone_marker_base(color, stone_frame);
  msg.type = visualization_msgs::Marker::TRIANGLE_LIST;
  msg.points.reserve(mesh.triangles.size() * 3);
  for (const auto& triangle : mesh.triangles) {
    for (const int index : triangle) msg.points.push_back(tf2::toMsg(mesh.vertices[index]));
  }
  return msg;
}

visualization_msgs::Marker to_mesh_marker_msg(const std::string& mesh_uri, const std::string& color,
                                              const std::string& stone_frame) {
  visualization_msgs::Marker msg = stone_marker_base(color, stone_frame);
  msg.type = visualization_msgs::Marker::MESH_RESOURCE;
  msg.mesh_resource = mesh_uri;
  return msg;
}

}  // namespace virtual_go
