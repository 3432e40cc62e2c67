// The board in rviz: sim/board_drawing as a visualization_msgs/MarkerArray in the world (fixed)
// frame. The board itself comes from the checked configuration (~board/enabled, ~board/size).
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "virtual_go/sim/board_drawing.h"

namespace virtual_go {

// Namespace "board": 0 the board (CUBE), 1 the table (CUBE), 2 the lines (LINE_LIST), 3 the
// star points (SPHERE_LIST, flat discs). Stamp 0 (the latest transform, whatever the clock);
// world_frame is the fixed frame, so the markers need no tf but the frame's existence.
visualization_msgs::MarkerArray to_board_markers_msg(const BoardDrawing& drawing,
                                                     const std::string& world_frame);

}  // namespace virtual_go
