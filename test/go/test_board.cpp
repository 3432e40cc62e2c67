// The board's coordinates against the real board's dimensions.
#include <gtest/gtest.h>

#include "virtual_go/common/validation.h"
#include "virtual_go/go/board.h"

namespace vg = virtual_go;

TEST(Board, RealSizeAndGrid) {
  const vg::BoardGeometry board;
  EXPECT_DOUBLE_EQ(board.table_z_m(), -0.1515);
  // Tengen (the centre point) is the origin; the corner points are 9 spacings away.
  EXPECT_NEAR(board.point_world(9, 9).norm(), 0.0, 1e-15);
  EXPECT_NEAR(board.point_world(0, 0).x(), -9 * 0.022, 1e-15);
  EXPECT_NEAR(board.point_world(18, 18).y(), 9 * 0.0237, 1e-15);
  // Nine star points, one of them tengen, the others on the 4th lines (3 spacings in).
  const auto stars = board.star_points_world();
  ASSERT_EQ(stars.size(), 9u);
  int at_centre = 0;
  for (const auto& p : stars) {
    if (p.norm() < 1e-15) ++at_centre;
    // Each coordinate is on the centre line or 6 spacings (the 4th line from the edge) away.
    EXPECT_TRUE(std::abs(p.x()) < 1e-15 || std::abs(std::abs(p.x()) - 6 * 0.022) < 1e-15) << p.x();
    EXPECT_TRUE(std::abs(p.y()) < 1e-15 || std::abs(std::abs(p.y()) - 6 * 0.0237) < 1e-15) << p.y();
  }
  EXPECT_EQ(at_centre, 1);
  // The grid fits with a margin: 18 * 22 mm = 396 mm < 424.2 mm.
  EXPECT_NO_THROW(vg::validate_board("~board/size", board));
}

TEST(Board, BadSizesNameTheFieldAndTheLimit) {
  vg::BoardGeometry board;
  board.thickness_m = -1;
  try {
    vg::validate_board("~board/size", board);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("~board/size: the thickness"), std::string::npos)
        << e.what();
  }
  board = vg::BoardGeometry();
  board.size_x_m = 0.3;  // the 396 mm grid does not fit
  EXPECT_THROW(vg::validate_board("~board/size", board), vg::InvalidArgument);
}
