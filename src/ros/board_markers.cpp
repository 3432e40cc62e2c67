#include "virtual_go/ros/board_markers.h"

namespace virtual_go {
namespace {

geometry_msgs::Point point_msg(const Eigen::Vector3d& p) {
  geometry_msgs::Point m;
  m.x = p.x();
  m.y = p.y();
  m.z = p.z();
  return m;
}

std_msgs::ColorRGBA color_msg(const Rgba& c) {
  std_msgs::ColorRGBA m;
  m.r = c[0];
  m.g = c[1];
  m.b = c[2];
  m.a = c[3];
  return m;
}

visualization_msgs::Marker base(int id, int type, const std::string& frame, const Rgba& color) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = ros::Time();
  m.ns = "board";
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color = color_msg(color);
  return m;
}

visualization_msgs::Marker box(int id, const DrawnBox& b, const std::string& frame,
                               const Rgba& color) {
  visualization_msgs::Marker m = base(id, visualization_msgs::Marker::CUBE, frame, color);
  m.pose.position = point_msg(b.center_world);
  m.scale.x = b.size.x();
  m.scale.y = b.size.y();
  m.scale.z = b.size.z();
  return m;
}

}  // namespace

visualization_msgs::MarkerArray to_board_markers_msg(const BoardDrawing& d,
                                                     const std::string& world_frame) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(box(0, d.board, world_frame, d.board_color));
  array.markers.push_back(box(1, d.table, world_frame, d.table_color));

  visualization_msgs::Marker lines =
      base(2, visualization_msgs::Marker::LINE_LIST, world_frame, d.ink_color);
  lines.scale.x = d.line_width_m;
  for (const DrawnSegment& s : d.lines) {
    lines.points.push_back(point_msg(s.from_world));
    lines.points.push_back(point_msg(s.to_world));
  }
  array.markers.push_back(lines);

  visualization_msgs::Marker stars =
      base(3, visualization_msgs::Marker::SPHERE_LIST, world_frame, d.ink_color);
  stars.scale.x = stars.scale.y = d.star_diameter_m;
  stars.scale.z = 0.1 * d.star_diameter_m;  // a flat disc on the board
  for (const Eigen::Vector3d& p : d.star_points_world) stars.points.push_back(point_msg(p));
  array.markers.push_back(stars);
  return array;
}

}  // namespace virtual_go
