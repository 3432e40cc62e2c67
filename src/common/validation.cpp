#include "virtual_go/common/validation.h"

#include <cmath>

namespace virtual_go {

void require_finite(const std::string& field, double value) {
  if (!std::isfinite(value)) {
    throw InvalidArgument(field, field + " must be finite, got " + format_value(value));
  }
}

void require_finite(const std::string& field, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    throw InvalidArgument(field, field + " must be finite, got " + format_vector(v));
  }
}

void require_positive(const std::string& field, double value) {
  require_finite(field, value);
  if (!(value > 0.0)) {
    throw InvalidArgument(field, field + " must be positive, got " + format_value(value));
  }
}

Eigen::Quaterniond require_unit_quaternion(const std::string& field, const Eigen::Quaterniond& q) {
  const Eigen::Vector4d c = q.coeffs();
  // The message text is built only on failure: this check runs on every validated state.
  auto text = [&c] {
    return "(x " + format_value(c[0]) + ", y " + format_value(c[1]) + ", z " + format_value(c[2]) +
           ", w " + format_value(c[3]) + ")";
  };
  if (!c.allFinite()) {
    throw InvalidArgument(field, field + " must be finite, got " + text());
  }
  double norm = c.norm();
  // Huge finite coefficients overflow the plain norm (giving a zero quaternion); scale instead.
  if (std::isinf(norm)) norm = c.stableNorm();
  if (!(norm > 1e-9)) {
    throw InvalidArgument(field, field + " must be a non-zero quaternion, got " + text());
  }
  return Eigen::Quaterniond(c / norm);
}

}  // namespace virtual_go
