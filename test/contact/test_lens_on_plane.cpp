// Contact kinematics of a lens on a horizontal plane, against independent references: the lens'
// support point (the lowest point, from its own geometry), the reach function's slope, and
// central finite differences of the offset along a rotation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "virtual_go/contact/lens_on_plane.h"

namespace vg = virtual_go;

namespace {

const vg::LensGeometry kLens(vg::LensShape(0.022, 0.0092));  // size 33

Eigen::Quaterniond random_orientation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// The lowest lens point relative to G, world frame, from the support function.
Eigen::Vector3d lowest_point(const Eigen::Quaterniond& q) {
  return q * kLens.support_body(q.conjugate() * Eigen::Vector3d(0, 0, -1));
}

}  // namespace

TEST(LensOnPlane, OffsetIsTheLowestPointOfTheLens) {
  std::mt19937 rng(3);
  double worst = 0.0;
  int rims = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Quaterniond q = random_orientation(rng);
    const Eigen::Vector3d b = q * Eigen::Vector3d::UnitZ();
    const vg::LensPart part = vg::lens_part_on_plane(kLens, b.z());
    rims += part == vg::LensPart::rim;
    const Eigen::Vector3d r = vg::plane_contact_offset_world(kLens, part, b);
    worst = std::max(worst, (r - lowest_point(q)).norm());
    // Height of G above the plane = reach.
    EXPECT_NEAR(-r.z(), kLens.reach(b.z()), 1e-17);
  }
  EXPECT_LT(worst, 1e-16);  // a few ulps of 15 mm
  EXPECT_GT(rims, 200);     // the sample covers the rim too
}

TEST(LensOnPlane, OffsetRateMatchesFiniteDifferencesAlongARotation) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n;
  double worst_relative = 0.0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Quaterniond q = random_orientation(rng);
    const Eigen::Vector3d omega(30 * n(rng), 30 * n(rng), 30 * n(rng));
    const Eigen::Vector3d b = q * Eigen::Vector3d::UnitZ();
    const vg::LensPart part = vg::lens_part_on_plane(kLens, b.z());
    const double h = 1e-7;
    auto offset_at = [&](double t) {
      const Eigen::Quaterniond qt =
          Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * t, omega.normalized())) * q;
      return vg::plane_contact_offset_world(kLens, part, qt * Eigen::Vector3d::UnitZ());
    };
    const Eigen::Vector3d fd = (offset_at(h) - offset_at(-h)) / (2 * h);
    const Eigen::Vector3d rate = vg::plane_contact_offset_rate_world(kLens, part, b, omega);
    worst_relative =
        std::max(worst_relative, (fd - rate).norm() / (kLens.half_width() * omega.norm()));
  }
  EXPECT_LT(worst_relative, 1e-7);
}

TEST(LensOnPlane, NormalVelocityOfTheContactPointIsTheGapRate) {
  // d/dt (h0 + rho(b_z)) = rho'(b_z) (omega x b)_z must equal -e_z . (omega x r).
  std::mt19937 rng(11);
  std::normal_distribution<double> n;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Quaterniond q = random_orientation(rng);
    const Eigen::Vector3d omega(20 * n(rng), 20 * n(rng), 20 * n(rng));
    const Eigen::Vector3d b = q * Eigen::Vector3d::UnitZ();
    const vg::LensPart part = vg::lens_part_on_plane(kLens, b.z());
    const Eigen::Vector3d r = vg::plane_contact_offset_world(kLens, part, b);
    const double height_rate = kLens.reach_slope(b.z()) * omega.cross(b).z();
    EXPECT_NEAR(-omega.cross(r).z(), height_rate, 1e-15 * (1 + omega.norm()));
  }
}
