// Lens vs plane, point and line against independent references: exact constructions (a point or
// line placed a chosen distance delta off the lens along a surface normal, so the distance is
// delta by construction), GJK on the lens's support mapping written in the test, and a
// brute-force scan over directions for the line's separating-axis gap (also when overlapping).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <random>

#include "support/convex_reference.h"
#include "support/flight_reference.h"
#include "virtual_go/geometry/lens_distance.h"

namespace vg = virtual_go;

namespace {

constexpr double kA = 0.011, kC = 0.0046;  // size 33: 22 x 9.2 mm
// Round-off of sums of centimetre-sized coordinates (ulp(0.03 m) = 3.5e-18 m), m.
constexpr double kRoundOff = 2e-16;

struct Fixture {
  vg::LensGeometry lens{vg::LensShape(2 * kA, 2 * kC)};
  std::mt19937 rng{12345};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};

  Eigen::Vector3d random_unit() {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  }
  vgtest::LensReference random_lens() {
    vgtest::LensReference ref{kA, kC};
    ref.x = Eigen::Vector3d(0.01 * normal(rng), 0.01 * normal(rng), 0.01 * normal(rng));
    ref.b = random_unit();
    return ref;
  }
  static vg::LensPose pose(const vgtest::LensReference& ref) {
    vg::LensPose p;
    p.center_world = ref.x;
    p.axis_world = ref.b;
    return p;
  }
  // A unit direction perpendicular to u.
  Eigen::Vector3d random_perpendicular(const Eigen::Vector3d& u) {
    const Eigen::Vector3d v = random_unit();
    return (v - v.dot(u) * u).normalized();
  }
};

// Which part of the reference lens a surface point lies on (-1 none).
vg::LensPart part_of(const vgtest::LensReference& ref, const Eigen::Vector3d& p) {
  const double r = ref.sphere_radius(), d = ref.sphere_offset();
  const Eigen::Vector3d local = p - ref.x;
  const double along = local.dot(ref.b);
  const double radial = (local - along * ref.b).norm();
  if (std::abs(along) < 1e-12 && std::abs(radial - ref.a) < 1e-12) return vg::LensPart::rim;
  if (std::abs((p - (ref.x + d * ref.b)).norm() - r) < 1e-12 && along <= 0) {
    return vg::LensPart::bottom_cap;
  }
  return vg::LensPart::top_cap;
}

TEST(LensDistance, PlaneGapIsTheSupportAlongTheNormal) {
  Fixture f;
  double worst_gap = 0, worst_point = 0;
  for (int k = 0; k < 2000; ++k) {
    const vgtest::LensReference ref = f.random_lens();
    const Eigen::Vector3d n = f.random_unit();
    const double h0 = 0.01 * f.normal(f.rng);
    const vg::LensContact c = vg::lens_gap_along(f.lens, Fixture::pose(ref), n, h0);
    const Eigen::Vector3d s = ref.support(-n);
    worst_gap = std::max(worst_gap, std::abs(c.gap_m - (n.dot(s) - h0)));
    worst_point = std::max(worst_point, (c.point_world - s).norm());
    EXPECT_EQ(c.normal_world, n);
    EXPECT_EQ(c.part, part_of(ref, c.point_world));
  }
  EXPECT_LT(worst_gap, kRoundOff);
  EXPECT_LT(worst_point, kRoundOff);
}

TEST(LensDistance, PointAtAKnownDistanceAlongASurfaceNormal) {
  // s = support(u) has outward normal u; p = s + delta u is delta from the lens and s is its
  // nearest point (u lies in the normal cone at s: a cap normal or within the rim's fan).
  Fixture f;
  double worst = 0, worst_normal = 0, worst_point = 0;
  int rim = 0, cap = 0;
  for (int k = 0; k < 4000; ++k) {
    const vgtest::LensReference ref = f.random_lens();
    const Eigen::Vector3d u = f.random_unit();
    const double delta = std::pow(10.0, -12.0 + 10.0 * f.uniform(f.rng));  // 1e-12 .. 1e-2 m
    const Eigen::Vector3d s = ref.support(u);
    const vg::LensContact c = vg::lens_point_distance(f.lens, Fixture::pose(ref), s + delta * u);
    worst = std::max(worst, std::abs(c.gap_m - delta) / (kRoundOff + 1e-14 * delta));
    // The normal is the direction of a delta-long difference of cm-sized coordinates: its error
    // times delta is a round-off-sized displacement (a rim point's normal is ill-conditioned as
    // delta -> 0; a cap's is not).
    worst_normal = std::max(worst_normal, (c.normal_world + u).norm() * delta / kRoundOff);
    worst_point = std::max(worst_point, (c.point_world - s).norm());
    (c.part == vg::LensPart::rim ? rim : cap)++;
  }
  EXPECT_LT(worst, 1.0);  // |gap - delta| < round-off + 1e-14 delta
  EXPECT_LT(worst_normal, 1.0);
  EXPECT_LT(worst_point, kRoundOff);
  EXPECT_GT(rim, 500);  // both closed forms exercised
  EXPECT_GT(cap, 500);
}

TEST(LensDistance, PointDistanceInsideTheGjkBracket) {
  Fixture f;
  int tested = 0;
  double worst_point = 0;
  for (int k = 0; k < 1000; ++k) {
    const vgtest::LensReference ref = f.random_lens();
    const Eigen::Vector3d p = ref.x + (0.5 + 1.5 * f.uniform(f.rng)) * kA * f.random_unit();
    if (ref.contains(p)) continue;
    const vgtest::GjkResult gjk = vgtest::gjk_distance(ref, vgtest::PointReference{p});
    ASSERT_FALSE(gjk.overlap);
    ASSERT_LT(gjk.upper - gjk.lower, 1e-12);
    const vg::LensContact c = vg::lens_point_distance(f.lens, Fixture::pose(ref), p);
    EXPECT_GE(c.gap_m, gjk.lower - 1e-15);
    EXPECT_LE(c.gap_m, gjk.upper + 1e-15);
    worst_point = std::max(worst_point, (c.point_world - gjk.point_a).norm());
    ++tested;
  }
  EXPECT_GT(tested, 500);
  EXPECT_LT(worst_point, 1e-6);  // GJK's witness converges like the square root of its gap
}

TEST(LensDistance, PointInsideIsMinusTheDistanceToTheBoundary) {
  // Reference: the nearest point of the boundary by a zooming grid search over its
  // parametrisation (each cap by polar angle and azimuth on its sphere, restricted to the cap),
  // written from the lens's definition.
  Fixture f;
  const vgtest::LensReference ref = f.random_lens();
  const double r = ref.sphere_radius(), d = ref.sphere_offset();
  const double alpha_max = std::asin(kA / r);
  const Eigen::Vector3d e1 = f.random_perpendicular(ref.b), e2 = ref.b.cross(e1);
  auto surface = [&](int side, double alpha, double phi) {  // side +1: top cap, -1: bottom
    alpha = std::clamp(alpha, 0.0, alpha_max);
    const Eigen::Vector3d radial = std::cos(phi) * e1 + std::sin(phi) * e2;
    return Eigen::Vector3d(ref.x + r * std::sin(alpha) * radial +
                           side * (r * std::cos(alpha) - d) * ref.b);
  };
  auto nearest_on_boundary = [&](const Eigen::Vector3d& p) {
    double best = 1e9;
    for (int side : {1, -1}) {
      double a0 = 0.5 * alpha_max, p0 = M_PI, da = 0.5 * alpha_max, dp = M_PI;
      for (int zoom = 0; zoom < 12; ++zoom) {
        double zoom_best = 1e9, best_a = a0, best_p = p0;
        for (int i = -20; i <= 20; ++i) {
          for (int j = -20; j <= 20; ++j) {
            const double a = std::clamp(a0 + da * i / 20, 0.0, alpha_max), ph = p0 + dp * j / 20;
            const double dist = (surface(side, a, ph) - p).norm();
            if (dist < zoom_best) {
              zoom_best = dist;
              best_a = a;
              best_p = ph;
            }
          }
        }
        a0 = best_a;
        p0 = best_p;
        da *= 0.15;
        dp *= 0.15;
        best = std::min(best, zoom_best);
      }
    }
    return best;
  };
  for (int k = 0; k < 40; ++k) {
    Eigen::Vector3d p;
    do {
      p = ref.x + kA * f.uniform(f.rng) * f.random_unit();
    } while (!ref.contains(p));
    const vg::LensContact c = vg::lens_point_distance(f.lens, Fixture::pose(ref), p);
    EXPECT_NEAR(c.gap_m, -nearest_on_boundary(p), 1e-13);
    // Moving the stone by -gap along the normal puts p on the surface.
    vgtest::LensReference moved = ref;
    moved.x += -c.gap_m * c.normal_world;
    const double r_b = (p - (moved.x + d * moved.b)).norm();
    const double r_t = (p - (moved.x - d * moved.b)).norm();
    EXPECT_NEAR(std::max(r_b, r_t), r, kRoundOff);
  }
}

TEST(LensDistance, LineAtAKnownDistanceFromATangentPlane) {
  // A line in the plane that supports the lens at s = support(u), lifted by delta along u, is
  // delta from the lens. Tiny deltas are where a sampled maximisation could miss the narrow arc
  // of positive gaps.
  Fixture f;
  double worst = 0;
  int rim = 0, cap = 0;
  for (int k = 0; k < 4000; ++k) {
    const vgtest::LensReference ref = f.random_lens();
    const Eigen::Vector3d u = f.random_unit();
    const Eigen::Vector3d e = f.random_perpendicular(u);
    const double delta = std::pow(10.0, -13.0 + 11.0 * f.uniform(f.rng));  // 1e-13 .. 1e-2 m
    const Eigen::Vector3d p0 = ref.support(u) + delta * u + 0.02 * f.normal(f.rng) * e;
    const vg::LensContact c = vg::lens_line_distance(f.lens, Fixture::pose(ref), p0, e);
    worst = std::max(worst, std::abs(c.gap_m - delta) / (kRoundOff + 1e-14 * delta));
    EXPECT_NEAR(c.normal_world.dot(e), 0.0, 4e-15);
    (c.part == vg::LensPart::rim ? rim : cap)++;
  }
  EXPECT_LT(worst, 1.0);  // |gap - delta| < round-off + 1e-14 delta
  EXPECT_GT(rim, 500);
  EXPECT_GT(cap, 500);
}

TEST(LensDistance, LineDistanceMatchesGjkAndTheDirectionScan) {
  Fixture f;
  int separated = 0, overlapping = 0;
  double worst_scan = 0, worst_normal = 0;
  for (int k = 0; k < 600; ++k) {
    const vgtest::LensReference ref = f.random_lens();
    const Eigen::Vector3d e = f.random_unit();
    // Lines passing up to 1.3 a from the centre: separated, grazing and overlapping.
    const Eigen::Vector3d p0 = ref.x + 1.3 * kA * f.uniform(f.rng) * f.random_perpendicular(e);
    const vg::LensContact c = vg::lens_line_distance(f.lens, Fixture::pose(ref), p0, e);
    Eigen::Vector3d scan_n;
    const double scan = vgtest::line_gap_by_scan(ref, p0, e, &scan_n);
    worst_scan = std::max(worst_scan, std::abs(c.gap_m - scan));
    if (scan > 1e-6) worst_normal = std::max(worst_normal, (c.normal_world - scan_n).norm());
    const vgtest::GjkResult gjk =
        vgtest::gjk_distance(ref, vgtest::SegmentReference{p0 - 0.5 * e, p0 + 0.5 * e});
    if (gjk.overlap) {
      EXPECT_LE(c.gap_m, 1e-15);
      ++overlapping;
    } else if (gjk.upper - gjk.lower < 1e-12) {
      EXPECT_GE(c.gap_m, gjk.lower - 1e-15);
      EXPECT_LE(c.gap_m, gjk.upper + 1e-15);
      ++separated;
    }
  }
  EXPECT_LT(worst_scan, 1e-14);
  EXPECT_LT(worst_normal, 1e-6);
  EXPECT_GT(separated, 100);
  EXPECT_GT(overlapping, 100);
}

}  // namespace
