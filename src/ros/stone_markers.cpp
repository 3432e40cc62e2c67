#include "virtual_go/ros/stone_markers.h"

#include <algorithm>
#include <stdexcept>

namespace virtual_go {

visualization_msgs::MarkerArray to_stone_markers_msg(
    const std::vector<StoneMarker>& stones, const std::vector<std::string>& drawn_before,
    const std::map<std::string, visualization_msgs::Marker>& prototypes) {
  visualization_msgs::MarkerArray array;
  for (const StoneMarker& s : stones) {
    const auto prototype = prototypes.find(s.color);
    if (prototype == prototypes.end()) {
      throw std::invalid_argument("no marker for stones of colour '" + s.color + "' (stone " +
                                  s.name + ")");
    }
    visualization_msgs::Marker m = prototype->second;
    m.header.frame_id = s.frame_id;
    m.header.stamp = ros::Time();  // zero: rviz draws it at the frame's latest transform
    m.frame_locked = true;
    m.ns = s.name;
    m.id = 0;
    m.action = visualization_msgs::Marker::ADD;
    m.pose = s.pose;
    array.markers.push_back(std::move(m));
  }
  for (const std::string& name : drawn_before) {
    const bool kept = std::any_of(stones.begin(), stones.end(),
                                  [&](const StoneMarker& s) { return s.name == name; });
    if (kept) continue;
    visualization_msgs::Marker m;
    m.ns = name;
    m.id = 0;
    m.action = visualization_msgs::Marker::DELETE;
    array.markers.push_back(std::move(m));
  }
  return array;
}

}  // namespace virtual_go
