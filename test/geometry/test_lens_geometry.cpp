// Lens contact geometry against an independent reference: the lens surface sampled from its
// definition (two sphere caps meeting at the rim) and brute-force maxima over the samples.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "virtual_go/geometry/lens_geometry.h"

namespace vg = virtual_go;

namespace {

// Points on the lens surface from its definition: for polar angle up to asin(a/R) on each
// sphere (centres at +/- d), full circle in azimuth.
std::vector<Eigen::Vector3d> surface_samples(double a, double c, int rings, int segments) {
  const double r = (a * a + c * c) / (2 * c), d = r - c;
  const double alpha_max = std::asin(a / r);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= rings; ++i) {
    const double alpha = alpha_max * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      const double rho = r * std::sin(alpha), z = r * std::cos(alpha) - d;
      points.emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);   // top cap
      points.emplace_back(rho * std::cos(phi), rho * std::sin(phi), -z);  // bottom cap
    }
  }
  return points;
}

TEST(LensGeometry, Size33SlateNumbers) {
  const vg::LensGeometry lens(vg::LensShape(0.022, 0.0092));
  EXPECT_NEAR(lens.half_width(), 0.011, 1e-15);
  EXPECT_NEAR(lens.half_height(), 0.0046, 1e-15);
  EXPECT_NEAR(lens.sphere_radius(), 15.4522e-3, 1e-7);
  EXPECT_NEAR(lens.sphere_offset(), 10.8522e-3, 1e-7);
  EXPECT_NEAR(lens.cos_cap_cone(), 0.70231, 1e-5);
  // Resting flat on the bottom cap: G is c above the plane.
  EXPECT_NEAR(lens.reach(1.0), 0.0046, 1e-15);
  // Standing on the rim: G is a above the plane.
  EXPECT_NEAR(lens.reach(0.0), 0.011, 1e-15);
}

TEST(LensGeometry, SupportAndReachMatchBruteForceOverTheSurface) {
  const double a = 0.011, c = 0.0046;
  const vg::LensGeometry lens(vg::LensShape(2 * a, 2 * c));
  const auto samples = surface_samples(a, c, 400, 720);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double worst_support = 0.0, worst_reach = 0.0;
  for (int k = 0; k < 200; ++k) {
    Eigen::Vector3d u(normal(rng), normal(rng), normal(rng));
    u.normalize();
    double best = -1e9;
    for (const auto& p : samples) best = std::max(best, u.dot(p));
    const Eigen::Vector3d s = lens.support_body(u);
    // The support value is the maximum over the surface (samples can only fall short).
    worst_support = std::max(worst_support, std::abs(u.dot(s) - best));
    // reach(ct) with n = -u in the body frame (b = e_z): max over the lens of -n . p = u . p.
    worst_reach = std::max(worst_reach, std::abs(lens.reach(-u.z()) - best));
    // The support point lies on the lens: on one of the spheres or the rim circle.
    const double r = lens.sphere_radius(), d = lens.sphere_offset();
    const double on_bottom = std::abs((s - Eigen::Vector3d(0, 0, d)).norm() - r);
    const double on_top = std::abs((s - Eigen::Vector3d(0, 0, -d)).norm() - r);
    EXPECT_LT(std::min(on_bottom, on_top), 1e-15);
  }
  // Sample spacing ~ R * 0.8 rad / 400 ~ 3e-5 m; a maximum is flat, so the error is second
  // order in the spacing (~1e-7 m). Any wrong switch (a/R instead of d/R) errs by ~1e-6 m.
  EXPECT_LT(worst_support, 3e-7);
  EXPECT_LT(worst_reach, 3e-7);
}

TEST(LensGeometry, ReachIsContinuouslyDifferentiableAcrossTheCapRimSwitch) {
  const vg::LensGeometry lens(vg::LensShape(0.022, 0.0092));
  const double s = lens.cos_cap_cone(), h = 1e-9;
  // No jump: across 2h the reach changes by the slope (-d) times 2h, to second order in h.
  EXPECT_NEAR(lens.reach(s - h) - lens.reach(s + h), 2 * h * lens.sphere_offset(), 1e-15);
  EXPECT_NEAR(lens.reach_slope(s - h), lens.reach_slope(s + h), 1e-5 * lens.sphere_offset());
  // The slope is the derivative of the reach (central differences away from the switch).
  for (double ct : {-0.95, -0.3, 0.0, 0.2, 0.69, 0.72, 0.99}) {
    const double e = 1e-6;
    EXPECT_NEAR(lens.reach_slope(ct), (lens.reach(ct + e) - lens.reach(ct - e)) / (2 * e), 1e-8)
        << ct;
    if (std::abs(std::abs(ct) - s) > 1e-3) {
      EXPECT_NEAR(lens.reach_curvature(ct),
                  (lens.reach_slope(ct + e) - lens.reach_slope(ct - e)) / (2 * e), 1e-6)
          << ct;
    }
    EXPECT_LE(std::abs(lens.reach_slope(ct)), lens.sphere_offset() * (1 + 1e-12));
  }
  EXPECT_EQ(lens.part_towards_plane(0.9), vg::LensPart::bottom_cap);
  EXPECT_EQ(lens.part_towards_plane(-0.9), vg::LensPart::top_cap);
  EXPECT_EQ(lens.part_towards_plane(0.5), vg::LensPart::rim);
}

}  // namespace
