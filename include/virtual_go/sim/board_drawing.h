// What rviz draws of the board (docs/physics.md, "World"), as plain data in the world frame, m:
// the board's box (its top face at z = 0), the table it stands on (a large thin slab whose top
// is at z = -thickness), the lines and the star points. ros/board_markers turns it into a
// visualization_msgs/MarkerArray; kept ROS-free so the geometry is tested without a master.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "virtual_go/go/board.h"

namespace virtual_go {

// An axis-aligned box: centre and full extents, m.
struct DrawnBox {
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

struct DrawnSegment {
  Eigen::Vector3d from_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d to_world = Eigen::Vector3d::Zero();
};

using Rgba = std::array<float, 4>;  // 0..1

struct BoardDrawing {
  DrawnBox board;
  DrawnBox table;
  // The lines x = const (running along y) first, then y = const; each spans the grid, from the
  // first line to the last. Drawn line_width_m wide, lifted above the top face (see
  // kLineLiftM) so they do not flicker against it.
  std::vector<DrawnSegment> lines;
  double line_width_m = 0.0;
  std::vector<Eigen::Vector3d> star_points_world;  // on the top face, lifted like the lines
  double star_diameter_m = 0.0;
  Rgba board_color{};
  Rgba table_color{};
  Rgba ink_color{};
};

// How far the lines and star points are drawn above the top face, m: 0.1 mm, well below what a
// stone on the board shows (its resting pose is exact; only the drawing is lifted).
constexpr double kLineLiftM = 1e-4;
// The table is drawn this wide each way around the board, and this thick, m.
constexpr double kTableMarginM = 1.0;
constexpr double kTableThicknessM = 0.002;

// Throws InvalidArgument (validate_board, field "board/size") for a board that cannot exist.
BoardDrawing make_board_drawing(const BoardGeometry& board);

}  // namespace virtual_go
