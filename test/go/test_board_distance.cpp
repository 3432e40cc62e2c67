// The stone vs the board (box) and the table against GJK on support mappings written in the
// test, over random poses around the board's faces, edges and corners and beside it; the
// feature is checked against where GJK's nearest board point lies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "support/convex_reference.h"
#include "virtual_go/go/board_distance.h"

namespace vg = virtual_go;

namespace {

constexpr double kA = 0.011, kC = 0.0046;
constexpr double kRoundOff = 2e-16;  // round-off of sums of sub-metre coordinates, m

struct Fixture {
  vg::BoardGeometry board;
  vg::LensGeometry lens{vg::LensShape(2 * kA, 2 * kC)};
  vg::BoardDistance distance{lens, board};
  double hx = 0.5 * board.size_x_m, hy = 0.5 * board.size_y_m, t = board.thickness_m;
  vgtest::BoxReference box{hx, hy, -t, 0.0};
  std::mt19937 rng{99};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};

  Eigen::Vector3d random_unit() {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  }
  static vg::LensPose pose(const vgtest::LensReference& ref) {
    vg::LensPose p;
    p.center_world = ref.x;
    p.axis_world = ref.b;
    return p;
  }
  // Reference distance to the table plane z = -t: the lens's lowest point.
  double table_gap(const vgtest::LensReference& ref) const {
    return ref.support(-Eigen::Vector3d::UnitZ()).z() + t;
  }
  // The feature holding the board point q (on the box surface, reached from outside).
  vg::BoardFeature feature_of(const Eigen::Vector3d& q) const {
    const double eps = 1e-9;
    const int sx = q.x() > hx - eps ? 1 : (q.x() < -hx + eps ? -1 : 0);
    const int sy = q.y() > hy - eps ? 1 : (q.y() < -hy + eps ? -1 : 0);
    const bool top = q.z() > -eps;
    auto side = [](int sx, int sy) { return sx > 0 ? 0 : sy > 0 ? 1 : sx < 0 ? 2 : 3; };
    auto quadrant = [](int sx, int sy) { return sx > 0 ? (sy > 0 ? 0 : 3) : (sy > 0 ? 1 : 2); };
    if (sx == 0 && sy == 0) return {vg::BoardFeatureKind::top_face, 0};
    if (sx != 0 && sy != 0) {
      return {top ? vg::BoardFeatureKind::top_corner : vg::BoardFeatureKind::vertical_edge,
              quadrant(sx, sy)};
    }
    return {top ? vg::BoardFeatureKind::top_edge : vg::BoardFeatureKind::side_face, side(sx, sy)};
  }
  // Distance of q from the boundaries between features (where the feature is ambiguous).
  double feature_margin(const Eigen::Vector3d& q) const {
    return std::min({std::abs(std::abs(q.x()) - hx) < 1e-9 ? 1.0 : std::abs(std::abs(q.x()) - hx),
                     std::abs(std::abs(q.y()) - hy) < 1e-9 ? 1.0 : std::abs(std::abs(q.y()) - hy),
                     std::abs(q.z()) < 1e-9 ? 1.0 : std::abs(q.z())});
  }
};

TEST(BoardDistance, MatchesGjkAroundFacesEdgesCornersAndTheTable) {
  Fixture f;
  int tested = 0, feature_checked = 0;
  std::map<vg::BoardFeatureKind, int> seen;
  double worst_point = 0, worst_normal = 0;
  for (int k = 0; k < 3000; ++k) {
    vgtest::LensReference ref{kA, kC};
    ref.b = f.random_unit();
    // Around the +x+y quarter of the board: over the face, near the edges, the corner, beside
    // the sides down to the table.
    const double u = f.uniform(f.rng);
    const double x = u < 0.3 ? f.hx * f.uniform(f.rng) : f.hx + 0.03 * (f.uniform(f.rng) - 0.4);
    const double y = u > 0.6 ? f.hy * f.uniform(f.rng) : f.hy + 0.03 * (f.uniform(f.rng) - 0.4);
    const double z =
        f.uniform(f.rng) < 0.7 ? 0.02 * f.uniform(f.rng) - 0.005 : -f.t + 0.05 * f.uniform(f.rng);
    ref.x = Eigen::Vector3d(x, y, z);
    const vgtest::GjkResult gjk = vgtest::gjk_distance(ref, f.box);
    const double table = f.table_gap(ref);
    if (gjk.overlap || table <= 0.0 || gjk.upper - gjk.lower > 1e-12) continue;
    const vg::BoardContact c = f.distance.nearest(Fixture::pose(ref));
    ++tested;
    if (table < gjk.lower) {
      EXPECT_NEAR(c.lens.gap_m, table, kRoundOff);
      EXPECT_EQ(c.feature.kind, vg::BoardFeatureKind::table);
      continue;
    }
    EXPECT_GE(c.lens.gap_m, gjk.lower - kRoundOff);
    EXPECT_LE(c.lens.gap_m, gjk.upper + kRoundOff);
    worst_point = std::max(worst_point, (c.lens.point_world - gjk.point_a).norm());
    // The witness minus gap times the normal is a point of the board's surface: a first-order
    // check of the normal (GJK's own normal is too rough for small gaps).
    const Eigen::Vector3d q = c.lens.point_world - c.lens.gap_m * c.lens.normal_world;
    const double outside =
        std::max({std::abs(q.x()) - f.hx, std::abs(q.y()) - f.hy, q.z(), -f.t - q.z()});
    const Eigen::Vector3d clamped(std::clamp(q.x(), -f.hx, f.hx), std::clamp(q.y(), -f.hy, f.hy),
                                  std::clamp(q.z(), -f.t, 0.0));
    worst_normal = std::max({worst_normal, std::abs(outside), (q - clamped).norm()});
    if (f.feature_margin(gjk.point_b) > 1e-6) {
      EXPECT_EQ(c.feature, f.feature_of(gjk.point_b))
          << vg::board_feature_name(c.feature) << " at " << ref.x.transpose();
      ++feature_checked;
      ++seen[c.feature.kind];
    }
  }
  EXPECT_GT(tested, 1500);
  EXPECT_GT(feature_checked, 1000);
  for (auto kind : {vg::BoardFeatureKind::top_face, vg::BoardFeatureKind::side_face,
                    vg::BoardFeatureKind::top_edge, vg::BoardFeatureKind::vertical_edge,
                    vg::BoardFeatureKind::top_corner}) {
    EXPECT_GT(seen[kind], 20) << static_cast<int>(kind);
  }
  EXPECT_LT(worst_point, 1e-6);  // GJK's witness is converged to ~sqrt(its gap bracket)
  EXPECT_LT(worst_normal, 1e-15);
}

TEST(BoardDistance, OneFeatureEqualsTheBoardWhereItIsNearest) {
  // A stone tilted over the +x top edge: the edge's own line distance is the board distance.
  Fixture f;
  vgtest::LensReference ref{kA, kC};
  ref.b = Eigen::Vector3d(std::sin(0.5), 0.0, std::cos(0.5));
  ref.x = Eigen::Vector3d(f.hx + 0.004, 0.05, 0.004);
  const vg::BoardContact board = f.distance.nearest(Fixture::pose(ref));
  ASSERT_EQ(board.feature, (vg::BoardFeature{vg::BoardFeatureKind::top_edge, 0}));
  const vg::BoardContact edge = f.distance.feature(Fixture::pose(ref), board.feature);
  EXPECT_EQ(edge.lens.gap_m, board.lens.gap_m);
  const vgtest::GjkResult gjk = vgtest::gjk_distance(ref, f.box);
  EXPECT_NEAR(edge.lens.gap_m, gjk.upper, 1e-15);
  // The normal points from the edge into the stone: up and outwards, perpendicular to y.
  EXPECT_GT(board.lens.normal_world.x(), 0.0);
  EXPECT_GT(board.lens.normal_world.z(), 0.0);
  EXPECT_NEAR(board.lens.normal_world.y(), 0.0, 1e-15);
}

TEST(BoardDistance, FlatStonesTouchExactlyAndSunkenStonesOverlap) {
  Fixture f;
  vg::LensPose pose;
  pose.center_world = Eigen::Vector3d(0.1, -0.05, kC);  // resting flat on the top face
  vg::BoardContact c = f.distance.nearest(pose);
  EXPECT_EQ(c.feature.kind, vg::BoardFeatureKind::top_face);
  EXPECT_NEAR(c.lens.gap_m, 0.0, 1e-18);
  EXPECT_EQ(c.lens.part, vg::LensPart::bottom_cap);
  EXPECT_NEAR(c.lens.point_world.z(), 0.0, 1e-18);
  pose.center_world = Eigen::Vector3d(f.hx + 0.05, 0.0, -f.t + kC);  // on the table beside it
  c = f.distance.nearest(pose);
  EXPECT_TRUE(c.on_table());
  EXPECT_NEAR(c.lens.gap_m, 0.0, 1e-17);
  pose.axis_world = -Eigen::Vector3d::UnitZ();  // upside down: the top cap touches
  c = f.distance.nearest(pose);
  EXPECT_EQ(c.lens.part, vg::LensPart::top_cap);
  EXPECT_NEAR(c.lens.gap_m, 0.0, 1e-17);
  // Sunk 1 mm into the middle of the top face: the overlap along the face normal.
  pose.axis_world = Eigen::Vector3d::UnitZ();
  pose.center_world = Eigen::Vector3d(0.0, 0.0, kC - 0.001);
  EXPECT_NEAR(f.distance.nearest(pose).lens.gap_m, -0.001, 1e-17);
  // Over the edge and sunk: never reported apart.
  pose.center_world = Eigen::Vector3d(f.hx + 0.003, 0.0, kC - 0.001);
  EXPECT_LT(f.distance.nearest(pose).lens.gap_m, 0.0);
}

TEST(BoardDistance, TheGapIsNeverAboveTheTrueDistance) {
  // Every separating axis is a lower bound: for random poses the board gap never exceeds GJK's
  // upper bound, overlapping poses included (then it is <= 0).
  Fixture f;
  int overlaps = 0;
  for (int k = 0; k < 2000; ++k) {
    vgtest::LensReference ref{kA, kC};
    ref.b = f.random_unit();
    ref.x =
        Eigen::Vector3d(f.hx + 0.02 * (f.uniform(f.rng) - 0.5),
                        f.hy + 0.02 * (f.uniform(f.rng) - 0.5), 0.02 * (f.uniform(f.rng) - 0.5));
    const vgtest::GjkResult gjk = vgtest::gjk_distance(ref, f.box);
    const double gap = f.distance.box(Fixture::pose(ref)).lens.gap_m;
    if (gjk.overlap) {
      ++overlaps;
      EXPECT_LE(gap, 0.0);
    } else {
      EXPECT_LE(gap, gjk.upper + kRoundOff);
    }
  }
  EXPECT_GT(overlaps, 200);
}

}  // namespace
