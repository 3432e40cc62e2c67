// Which board contacts are a plane with an exact model, the table's clearance to the board, and
// placing a stone exactly on a plane; the reach is the test's own lens support.
#include <gtest/gtest.h>

#include "virtual_go/world/support_plane.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

vg::BoardDistance board_distance() {
  return vg::BoardDistance(vg::LensGeometry(stone().shape), vg::BoardGeometry{});
}

TEST(SupportPlane, TheTopFaceInsideItsRectangleIsAPlane) {
  const auto board = board_distance();
  const vg::RigidBodyState s = at(Vector3d(0.1, 0.05, kC));
  const vg::BoardContact c = board.nearest(s);
  const auto plane = vg::support_plane(board, c, vg::lens_pose(s), 0.0);
  ASSERT_TRUE(plane.has_value());
  EXPECT_EQ(plane->feature.kind, vg::BoardFeatureKind::top_face);
  EXPECT_EQ(plane->height_m, 0.0);
  EXPECT_TRUE(plane->region.contains(Eigen::Vector2d(0.1, 0.05)));
  EXPECT_FALSE(plane->region.contains(Eigen::Vector2d(kHalfX + 1e-6, 0.0)));
  // Closer to the edge than the margin: not handed to the plane model.
  const vg::RigidBodyState near_edge = at(Vector3d(kHalfX - 5e-6, 0.0, kC));
  EXPECT_FALSE(vg::support_plane(board, board.nearest(near_edge), vg::lens_pose(near_edge), 1e-5)
                   .has_value());
  EXPECT_TRUE(vg::support_plane(board, board.nearest(near_edge), vg::lens_pose(near_edge), 1e-6)
                  .has_value());
}

TEST(SupportPlane, AnEdgeIsNotAPlane) {
  const auto board = board_distance();
  // Flat, centre 2 mm beyond the +x edge, the cap's sphere touching the edge line.
  const double z = std::sqrt(kR * kR - 0.002 * 0.002) - kD;
  const vg::RigidBodyState s = at(Vector3d(kHalfX + 0.002, 0.0, z));
  const vg::BoardContact c = board.nearest(s);
  EXPECT_EQ(c.feature.kind, vg::BoardFeatureKind::top_edge);
  EXPECT_FALSE(vg::support_plane(board, c, vg::lens_pose(s), 0.0).has_value());
}

TEST(SupportPlane, TheTableBesideTheBoardIsAPlaneWhileClearOfTheSides) {
  const auto board = board_distance();
  const double x = kHalfX + kA + 0.005;  // 5 mm from the side face
  const vg::RigidBodyState s = at(Vector3d(x, 0.0, -kThickness + kC));
  const vg::BoardContact c = board.nearest(s);
  EXPECT_EQ(c.feature.kind, vg::BoardFeatureKind::table);
  const auto plane = vg::support_plane(board, c, vg::lens_pose(s), 0.0);
  ASSERT_TRUE(plane.has_value());
  EXPECT_EQ(plane->height_m, -kThickness);
  EXPECT_TRUE(plane->region.contains(Eigen::Vector2d(x, 0.0)));
  EXPECT_FALSE(plane->region.contains(Eigen::Vector2d(0.0, 0.0)));  // under the board
  const auto clearance = vg::support_plane_clearance(board, *plane);
  ASSERT_TRUE(static_cast<bool>(clearance));
  EXPECT_NEAR(clearance(vg::lens_pose(s)), 0.005, 1e-15);  // the rim to the side face
  // Touching the side: no longer a plane of its own.
  const vg::RigidBodyState touching = at(Vector3d(kHalfX + kA, 0.0, -kThickness + kC));
  EXPECT_FALSE(
      vg::support_plane(board, board.nearest(touching), vg::lens_pose(touching), 0.0).has_value());
  // The top face needs no clearance: a lens whose lowest point is on it is above the box.
  vg::SupportPlane top{{vg::BoardFeatureKind::top_face, 0}, 0.0, vg::PlaneRegion::whole_plane()};
  EXPECT_FALSE(static_cast<bool>(vg::support_plane_clearance(board, top)));
}

TEST(SupportPlane, PlacedOnAPlaneTouchesItExactly) {
  const vg::LensGeometry lens(stone().shape);
  for (const double tilt : {0.0, 0.3, 0.9, 1.2, 2.0, 3.0}) {
    const Quaterniond q(Eigen::AngleAxisd(tilt, Vector3d(0.3, 1, 0).normalized()));
    const vg::RigidBodyState s = vg::placed_on_plane(lens, at(Vector3d(0.1, 0.2, 0.3), q), -0.05);
    EXPECT_NEAR(plane_gap(s, -0.05), 0.0, 1e-16) << tilt;
    EXPECT_EQ(s.position_world.x(), 0.1);
    EXPECT_EQ(s.position_world.y(), 0.2);
  }
}

}  // namespace
