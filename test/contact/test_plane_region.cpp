// The plane's region: the sign of its margin says inside or outside, and bad sizes are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_go/contact/plane_region.h"
#include "virtual_go/go/board.h"
#include "virtual_go/common/validation.h"

namespace vg = virtual_go;

TEST(PlaneRegion, BoardTopAndTableAroundIt) {
  const vg::BoardGeometry board;
  const auto top = vg::PlaneRegion::inside(Eigen::Vector2d::Zero(), board.half_extent_m());
  const auto table = vg::PlaneRegion::outside(Eigen::Vector2d::Zero(), board.half_extent_m());
  const Eigen::Vector2d centre(0.0, 0.0), near_edge(0.2, 0.1), beyond(0.25, 0.0);
  EXPECT_TRUE(top.contains(centre));
  EXPECT_TRUE(top.contains(near_edge));
  EXPECT_FALSE(top.contains(beyond));
  EXPECT_FALSE(table.contains(centre));
  EXPECT_TRUE(table.contains(beyond));
  // The margin inside is the distance to the nearest side: 0.2121 - 0.2 across.
  EXPECT_NEAR(top.margin_m(near_edge), 0.5 * 0.4242 - 0.2, 1e-15);
  EXPECT_NEAR(table.margin_m(near_edge), -(0.5 * 0.4242 - 0.2), 1e-15);
  // Zero on the boundary, and continuous across it.
  EXPECT_EQ(top.margin_m(Eigen::Vector2d(0.5 * 0.4242, 0.0)), 0.0);
  EXPECT_TRUE(std::isinf(vg::PlaneRegion::whole_plane().margin_m(beyond)));
}

TEST(PlaneRegion, BadSizesAreRefusedByName) {
  auto r = vg::PlaneRegion::inside(Eigen::Vector2d::Zero(), Eigen::Vector2d(0.1, 0.0));
  try {
    vg::validate_region("board_top", r);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("board_top.half_extent.y"), std::string::npos);
  }
  r.half_extent_m.y() = 0.1;
  r.center_world_m.x() = NAN;
  EXPECT_THROW(vg::validate_region("board_top", r), vg::InvalidArgument);
  EXPECT_NO_THROW(vg::validate_region("table", vg::PlaneRegion::whole_plane()));
}
