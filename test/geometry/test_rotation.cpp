// Quaternion helpers: the exponential map against the axis-angle rotation (including angles far
// below where cos-based formulas lose accuracy) and the geodesic orientation error.
#include <gtest/gtest.h>

#include <limits>

#include "support/physics_reference.h"
#include "virtual_go/geometry/rotation.h"

namespace vg = virtual_go;

TEST(Rotation, ExponentialMapIsTheAxisAngleRotation) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
  for (double angle : {0.0, 1e-20, 1e-9, 0.3, 1.0, M_PI / 2, 3.0, M_PI, 7.0}) {
    const Eigen::Quaterniond q = vg::rotation_exp(angle * axis);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15) << angle;
    // (cos(angle/2), sin(angle/2) axis), compared component-wise with relative accuracy so that
    // the tiny-angle vector part (~angle/2) is checked to full precision too.
    const vgtest::Quat expected = vgtest::axis_angle(angle * axis);
    EXPECT_NEAR(q.w(), expected[0], 1e-15) << angle;
    for (int i = 0; i < 3; ++i) {
      const double scale = angle < 1e-3 ? std::abs(expected[i + 1]) : 1.0;
      EXPECT_NEAR(q.vec()[i], expected[i + 1], 1e-15 * scale) << angle;
    }
    // Rotating a vector: x' = x cos + (k x x) sin + k (k . x)(1 - cos) (Rodrigues).
    const Eigen::Vector3d x(0.3, 0.5, -0.8);
    const Eigen::Vector3d rodrigues = x * std::cos(angle) + axis.cross(x) * std::sin(angle) +
                                      axis * axis.dot(x) * (1 - std::cos(angle));
    EXPECT_LT((q * x - rodrigues).norm(), 1e-15) << angle;
  }
}

TEST(Rotation, OrientationErrorIsTheGeodesicAngle) {
  const vgtest::Quat p = vgtest::axis_angle(Eigen::Vector3d(0.4, -1.2, 0.9));
  const Eigen::Vector3d axis = Eigen::Vector3d(2.0, 3.0, -6.0) / 7.0;
  for (double angle : {0.0, 1e-14, 1e-10, 1e-8, 0.5, 2.0, 3.1}) {
    const vgtest::Quat q = vgtest::qmul(p, vgtest::axis_angle(angle * axis));
    const double e = vg::orientation_error(vgtest::to_eigen(p), vgtest::to_eigen(q));
    EXPECT_NEAR(e, angle, 1e-15 + 1e-14 * angle) << angle;
    // q and -q are the same orientation.
    EXPECT_NEAR(vg::orientation_error(vgtest::to_eigen(p), vgtest::to_eigen(-q)), angle,
                1e-15 + 1e-14 * angle)
        << angle;
  }
  // Beyond pi the short way round is taken: 2 pi - angle.
  const vgtest::Quat far = vgtest::qmul(p, vgtest::axis_angle(4.0 * axis));
  EXPECT_NEAR(vg::orientation_error(vgtest::to_eigen(p), vgtest::to_eigen(far)), 2 * M_PI - 4.0,
              1e-14);
}

// q * v without intermediate overflow (issue 8: ~odom's twist for |v| > 9e307): against the
// rotation matrix on the scaled vector, and equal to the plain product where that is finite.
TEST(Rotation, RotateWithoutOverflowMatchesTheMatrixAtAnyScale) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.3, -0.9, 0.2, 0.25).normalized();
  const Eigen::Vector3d direction = Eigen::Vector3d(0.2, 1.0, -0.4).normalized();
  for (const double length : {1e-300, 1.0, 1e150, 1e200, 9e307, 1.7e308}) {
    const Eigen::Vector3d v = length * direction;
    const Eigen::Vector3d r = vg::rotate_without_overflow(q, v);
    ASSERT_TRUE(r.allFinite()) << length;
    const Eigen::Vector3d expected = (q.toRotationMatrix() * direction) * length;
    EXPECT_LT(((r - expected) / length).norm(), 1e-15) << length;
    if (length <= 1e150) EXPECT_EQ(r, Eigen::Vector3d(q * v)) << "the plain product below 1e150";
  }
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(vg::rotate_without_overflow(q, Eigen::Vector3d(inf, 0, 0)).allFinite());
}
