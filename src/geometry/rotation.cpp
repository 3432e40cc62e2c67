#include "virtual_go/geometry/rotation.h"

#include <cmath>

#include "virtual_go/common/validation.h"

namespace virtual_go {

Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& v) {
  double angle = v.norm();
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  if (!std::isfinite(angle)) {
    // Non-finite input is an error; a huge finite one only overflowed the plain norm.
    require_finite("rotation vector", v);
    angle = v.stableNorm();
  }
  const double half = 0.5 * angle;
  // sin(half)/angle computed directly keeps full relative accuracy for tiny angles.
  const double s = std::sin(half) / angle;
  return Eigen::Quaterniond(std::cos(half), s * v.x(), s * v.y(), s * v.z());
}

Eigen::Vector3d rotate_without_overflow(const Eigen::Quaterniond& q, const Eigen::Vector3d& v) {
  // Below 1e150 every intermediate of the plain product is below 4e150: no overflow.
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 1e150) || std::isinf(largest)) return q * v;
  return (q * Eigen::Vector3d(v / largest)) * largest;
}

double orientation_error(const Eigen::Quaterniond& reference, const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond d = reference.conjugate() * q;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace virtual_go
