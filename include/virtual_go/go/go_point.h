// Points (intersections) of the 19 x 19 Go board: their names in GTP ("A1" ... "T19") and in SGF
// ("aa" ... "ss"), and where they are in the world.
//
// GTP names a point by a column letter A ... T, skipping I, left to right, and a row number 1 ...
// 19 from the bottom of a diagram: A1 is the lower-left corner, K10 the centre (tengen), T19 the
// upper right. SGF names it by two lowercase letters, column then row, counted from the top-left
// corner with `i` used: "aa" is A19, "ss" is T1, "jj" is K10 (red-bean.com/sgf/go.html).
//
// In the world (BoardGeometry, go/board.h): x runs across the columns (A at -x, T at +x) and y
// along the rows (row 1 at -y, the side nearest the player with black, row 19 at +y). Looking
// down the z axis with x to the right and y up (rviz's top-down view, REP 103's map view), the
// board reads like a Go diagram, A1 lower left. GoPoint{column, row} is BoardGeometry's
// point_world(column, row).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "virtual_go/go/board.h"

namespace virtual_go {

constexpr int kGoLines = 19;  // the only board size Go points are defined for here

struct GoPoint {
  int column = 0;  // 0 = A ... 18 = T (GTP's letters skip I), towards +x
  int row = 0;     // 0 = GTP row 1 ... 18 = row 19, towards +y

  friend bool operator==(GoPoint a, GoPoint b) { return a.column == b.column && a.row == b.row; }
  friend bool operator!=(GoPoint a, GoPoint b) { return !(a == b); }
  // Row-major from A1, so sorted points read A1 B1 ... T1 A2 ...
  friend bool operator<(GoPoint a, GoPoint b) {
    return a.row != b.row ? a.row < b.row : a.column < b.column;
  }
};

// Whether Go points are defined on this board: only on one of kGoLines lines. The one test of
// that fact; no_go_points_reason says why not, for every caller's message.
bool has_go_points(const BoardGeometry& board);
// "Go points need 19 lines, the board has 13" (no field prefix).
std::string no_go_points_reason(const BoardGeometry& board);

// Both indices in 0 .. kGoLines-1.
bool is_on_grid(GoPoint point);
// row * 19 + column, 0 .. 360, for arrays of the board's points; the point must be on the grid.
int point_index(GoPoint point);
GoPoint point_at_index(int index);

// "A1" ... "T19". Letters in either case, no spaces, no leading zeros. Anything else throws
// InvalidArgument (field "point") naming the input and the valid range.
GoPoint parse_gtp_point(const std::string& name);
// Upper case, e.g. "K10". Throws InvalidArgument (field "point") for a point off the grid.
std::string gtp_name(GoPoint point);

// Two lowercase letters "aa" ... "ss" (a pass, "" or "tt", is not a point: the SGF reader handles
// it). Anything else throws InvalidArgument (field "sgf point") naming the input and the range.
GoPoint parse_sgf_point(const std::string& letters);
std::string sgf_name(GoPoint point);

// The intersection's world position (m) on the board's top face. The board must have 19 lines
// (InvalidArgument, field "board", otherwise).
Eigen::Vector3d go_point_world(const BoardGeometry& board, GoPoint point);

// The intersection nearest to a world position, by x and y only (a stone above the board, or one
// nudged off its point, belongs to the point below its centre). None when the position is off the
// grid: more than half a spacing outside the outer lines (|x| > 9.5 spacing_x or |y| > 9.5
// spacing_y from tengen), or not finite. A position exactly halfway between two lines goes to the
// line farther from tengen (rounding half away from zero). The board must have 19 lines.
std::optional<GoPoint> nearest_go_point(const BoardGeometry& board,
                                        const Eigen::Vector3d& position_world);
// The GTP name of nearest_go_point, or "" when there is none (as ~stones' `point` field).
std::string nearest_go_point_name(const BoardGeometry& board,
                                  const Eigen::Vector3d& position_world);

}  // namespace virtual_go
