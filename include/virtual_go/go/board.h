// The Go board: a box whose top face is the playing surface at world z = 0, centred on the
// origin (the board's centre point, tengen), standing on a table plane at z = -thickness. The
// defaults are a real table board (goban): 424.2 x 454.5 mm, 151.5 mm thick, lines 22 mm apart
// across (x) and 23.7 mm along (y), 1 mm wide, star points 4 mm across.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace virtual_go {

struct BoardGeometry {
  double size_x_m = 0.4242;        // across, m
  double size_y_m = 0.4545;        // along (towards the players), m
  double thickness_m = 0.1515;     // m; the table is at z = -thickness
  int lines = 19;                  // lines each way
  double spacing_x_m = 0.022;      // m between lines along x
  double spacing_y_m = 0.0237;     // m between lines along y
  double line_width_m = 0.001;     // m
  double star_diameter_m = 0.004;  // m

  double top_z_m() const { return 0.0; }
  double table_z_m() const { return -thickness_m; }
  Eigen::Vector2d half_extent_m() const { return {0.5 * size_x_m, 0.5 * size_y_m}; }
  // The world position (m) of the intersection at column i, row j (0 .. lines-1), on the top.
  Eigen::Vector3d point_world(int i, int j) const;
  // Star points (hoshi): for 19 lines the 3-9-15 pattern, 0-based indices.
  std::vector<Eigen::Vector3d> star_points_world() const;
};

// Throws InvalidArgument with field() `field` (e.g. "board/size"), naming the size, the value and
// the limit: sizes positive, finite and at most kMaxBoardSizeM; the grid must fit on the top face.
void validate_board(const std::string& field, const BoardGeometry& board);

constexpr double kMaxBoardSizeM = 100.0;

}  // namespace virtual_go
