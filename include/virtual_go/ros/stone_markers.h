// Every stone in rviz as one visualization_msgs/MarkerArray (~stone_markers), built from a list
// of (name, colour, pose) so that a board of many stones is one message, and a stone no longer
// listed is deleted.
//
// A stone's marker is keyed by its name: ns = the name, id 0, so adding, replacing and deleting
// need no table of ids. Its shape is the prototype of its colour (a mesh per colour: black and
// white stones differ in size; ros/stone_messages.h makes the MESH_RESOURCE or TRIANGLE_LIST).
// The node draws each stone in its own tf frame (frame_id = the name, identity pose,
// frame_locked) as ~marker always has, so rviz moves it with /tf and the array is only re-sent
// when stones come or go (and every second, for rviz's sake: stone_node.cpp says why).
#pragma once

#include <geometry_msgs/Pose.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <map>
#include <string>
#include <vector>

namespace virtual_go {

struct StoneMarker {
  std::string name;      // the stone's name: the marker's ns
  std::string color;     // "black" | "white": which prototype draws it
  std::string frame_id;  // the frame `pose` is in: the stone's own frame, or the world frame
  geometry_msgs::Pose pose;
};

// ADD (a full marker) for every stone, then DELETE for every name in `drawn_before` not among
// them. prototypes: the marker per colour (shape, scale, colour); a stone of a colour without
// one throws std::invalid_argument naming the colour.
visualization_msgs::MarkerArray to_stone_markers_msg(
    const std::vector<StoneMarker>& stones, const std::vector<std::string>& drawn_before,
    const std::map<std::string, visualization_msgs::Marker>& prototypes);

}  // namespace virtual_go
