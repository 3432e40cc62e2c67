// The board's drawing (sim/board_drawing): the box and the table where the physics has them, the
// 19 x 19 lines at the board's spacing across the whole grid, the 9 star points of the 3-9-15
// pattern, all from the real board's numbers written here (424.2 x 454.5 x 151.5 mm, lines
// 22 x 23.7 mm apart, 1 mm wide, star points 4 mm).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "virtual_go/common/validation.h"
#include "virtual_go/sim/board_drawing.h"

namespace {

namespace vg = virtual_go;
constexpr double kSizeX = 0.4242, kSizeY = 0.4545, kThickness = 0.1515;
constexpr double kSpacingX = 0.022, kSpacingY = 0.0237;
constexpr double kTol = 1e-15;

TEST(BoardDrawing, BoxTopAtZeroBottomOnTheTable) {
  const vg::BoardDrawing d = vg::make_board_drawing(vg::BoardGeometry{});
  EXPECT_NEAR(d.board.size.x(), kSizeX, kTol);
  EXPECT_NEAR(d.board.size.y(), kSizeY, kTol);
  EXPECT_NEAR(d.board.size.z(), kThickness, kTol);
  EXPECT_NEAR(d.board.center_world.x(), 0.0, kTol);
  EXPECT_NEAR(d.board.center_world.y(), 0.0, kTol);
  EXPECT_NEAR(d.board.center_world.z() + 0.5 * d.board.size.z(), 0.0, kTol);          // top
  EXPECT_NEAR(d.board.center_world.z() - 0.5 * d.board.size.z(), -kThickness, kTol);  // bottom
  // The table: its top face is the plane the board stands on, much larger than the board.
  EXPECT_NEAR(d.table.center_world.z() + 0.5 * d.table.size.z(), -kThickness, kTol);
  EXPECT_GT(d.table.size.z(), 0.0);
  EXPECT_GE(d.table.size.x(), kSizeX + 1.0);
  EXPECT_GE(d.table.size.y(), kSizeY + 1.0);
}

TEST(BoardDrawing, NineteenLinesEachWayAcrossTheGrid) {
  const vg::BoardDrawing d = vg::make_board_drawing(vg::BoardGeometry{});
  ASSERT_EQ(d.lines.size(), 38u);
  EXPECT_EQ(d.line_width_m, 0.001);
  const double half_x = 9 * kSpacingX, half_y = 9 * kSpacingY;  // the grid: 396 x 426.6 mm
  std::set<long> along_y_at_x, along_x_at_y;                    // in um
  for (std::size_t k = 0; k < d.lines.size(); ++k) {
    const vg::DrawnSegment& s = d.lines[k];
    EXPECT_NEAR(s.from_world.z(), vg::kLineLiftM, kTol) << k;
    EXPECT_NEAR(s.to_world.z(), vg::kLineLiftM, kTol) << k;
    const bool along_y = std::abs(s.from_world.x() - s.to_world.x()) < kTol;
    EXPECT_EQ(along_y, k < 19) << k;
    if (along_y) {
      EXPECT_NEAR(std::min(s.from_world.y(), s.to_world.y()), -half_y, 1e-12) << k;
      EXPECT_NEAR(std::max(s.from_world.y(), s.to_world.y()), half_y, 1e-12) << k;
      along_y_at_x.insert(std::lround(s.from_world.x() * 1e6));
    } else {
      EXPECT_NEAR(s.from_world.y(), s.to_world.y(), kTol) << k;
      EXPECT_NEAR(std::min(s.from_world.x(), s.to_world.x()), -half_x, 1e-12) << k;
      EXPECT_NEAR(std::max(s.from_world.x(), s.to_world.x()), half_x, 1e-12) << k;
      along_x_at_y.insert(std::lround(s.from_world.y() * 1e6));
    }
  }
  std::set<long> expected_x, expected_y;
  for (int i = -9; i <= 9; ++i) {
    expected_x.insert(std::lround(i * kSpacingX * 1e6));
    expected_y.insert(std::lround(i * kSpacingY * 1e6));
  }
  EXPECT_EQ(along_y_at_x, expected_x);
  EXPECT_EQ(along_x_at_y, expected_y);
  // The grid lies on the top face, inside its edges.
  EXPECT_LT(half_x + 0.5 * d.line_width_m, 0.5 * kSizeX);
  EXPECT_LT(half_y + 0.5 * d.line_width_m, 0.5 * kSizeY);
}

TEST(BoardDrawing, NineStarPointsOnTheFourthLinesAndTengen) {
  const vg::BoardDrawing d = vg::make_board_drawing(vg::BoardGeometry{});
  ASSERT_EQ(d.star_points_world.size(), 9u);
  EXPECT_EQ(d.star_diameter_m, 0.004);
  std::set<std::pair<long, long>> found, expected;
  for (const Eigen::Vector3d& p : d.star_points_world) {
    EXPECT_NEAR(p.z(), vg::kLineLiftM, kTol);
    found.insert({std::lround(p.x() * 1e6), std::lround(p.y() * 1e6)});
  }
  for (int i : {-6, 0, 6}) {  // lines 4, 10, 16 of 19: 6 lines from the centre
    for (int j : {-6, 0, 6}) {
      expected.insert({std::lround(i * kSpacingX * 1e6), std::lround(j * kSpacingY * 1e6)});
    }
  }
  EXPECT_EQ(found, expected);
}

TEST(BoardDrawing, AnotherSizeMovesTheTable) {
  vg::BoardGeometry board;
  board.size_x_m = 0.5;
  board.size_y_m = 0.6;
  board.thickness_m = 0.03;
  const vg::BoardDrawing d = vg::make_board_drawing(board);
  EXPECT_NEAR(d.board.size.x(), 0.5, kTol);
  EXPECT_NEAR(d.table.center_world.z() + 0.5 * d.table.size.z(), -0.03, kTol);
  EXPECT_EQ(d.lines.size(), 38u);  // same grid on a larger board
}

TEST(BoardDrawing, ImpossibleBoardIsRefusedByName) {
  vg::BoardGeometry board;
  board.size_x_m = 0.3;  // the 396 mm grid does not fit
  try {
    vg::make_board_drawing(board);
    ADD_FAILURE() << "no throw";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "board/size");
    EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
  }
  board.size_x_m = -1.0;
  EXPECT_THROW(vg::make_board_drawing(board), vg::InvalidArgument);
}

}  // namespace
