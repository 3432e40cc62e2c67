#include "virtual_go/sim/board_drawing.h"

namespace virtual_go {

BoardDrawing make_board_drawing(const BoardGeometry& board) {
  validate_board("board/size", board);
  BoardDrawing d;
  d.board.center_world = Eigen::Vector3d(0.0, 0.0, board.top_z_m() - 0.5 * board.thickness_m);
  d.board.size = Eigen::Vector3d(board.size_x_m, board.size_y_m, board.thickness_m);
  d.table.center_world = Eigen::Vector3d(0.0, 0.0, board.table_z_m() - 0.5 * kTableThicknessM);
  d.table.size = Eigen::Vector3d(board.size_x_m + 2.0 * kTableMarginM,
                                 board.size_y_m + 2.0 * kTableMarginM, kTableThicknessM);
  const Eigen::Vector3d lift(0.0, 0.0, kLineLiftM);
  const int last = board.lines - 1;
  for (int i = 0; i < board.lines; ++i) {
    d.lines.push_back({board.point_world(i, 0) + lift, board.point_world(i, last) + lift});
  }
  for (int j = 0; j < board.lines; ++j) {
    d.lines.push_back({board.point_world(0, j) + lift, board.point_world(last, j) + lift});
  }
  d.line_width_m = board.line_width_m;
  for (const Eigen::Vector3d& p : board.star_points_world())
    d.star_points_world.push_back(p + lift);
  d.star_diameter_m = board.star_diameter_m;
  // Kaya-like yellow wood, a grey table, dark brown ink: darker than the wood, lighter than a
  // black stone, so a black stone still stands out on the lines.
  d.board_color = {0.86f, 0.70f, 0.36f, 1.0f};
  d.table_color = {0.55f, 0.55f, 0.58f, 1.0f};
  d.ink_color = {0.35f, 0.26f, 0.14f, 1.0f};
  return d;
}

}  // namespace virtual_go
