// The board in rviz: sim/board_drawing as a visualization_msgs/MarkerArray in the world (fixed)
// frame, and the minimal reading of ~board/enabled and ~board/size it needs.
#pragma once

#include <ros/node_handle.h>
#include <visualization_msgs/MarkerArray.h>

#include <optional>
#include <string>

#include "virtual_go/sim/board_drawing.h"

namespace virtual_go {

// The board the node simulates, or nothing when ~board/enabled is false (the default). Throws
// ConfigError naming ~board/enabled or ~board/size for a wrong type, length or size.
// TODO(merge): the parameter table (sim/stone_parameters) gains ~board/*; read it from the
// checked config then, not here.
std::optional<BoardGeometry> read_board_parameters(const ros::NodeHandle& private_nh);

// Namespace "board": 0 the board (CUBE), 1 the table (CUBE), 2 the lines (LINE_LIST), 3 the
// star points (SPHERE_LIST, flat discs). Stamp 0 (the latest transform, whatever the clock);
// world_frame is the fixed frame, so the markers need no tf but the frame's existence.
visualization_msgs::MarkerArray to_board_markers_msg(const BoardDrawing& drawing,
                                                     const std::string& world_frame);

}  // namespace virtual_go
