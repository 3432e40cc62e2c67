#include "virtual_go/common/validation.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace virtual_go {

std::string format_value(double value) {
  // The shortest precision that reads back as the same double, so that 0.009 prints as given
  // and not as 0.0089999999999999993; 17 digits always round-trip.
  std::ostringstream out;
  for (int precision = 15; precision <= 17; ++precision) {
    out.str("");
    out.precision(precision);
    out << value;
    if (std::strtod(out.str().c_str(), nullptr) == value) break;
  }
  return out.str();
}

std::string format_vector(const Eigen::Vector3d& v) {
  return "(" + format_value(v.x()) + ", " + format_value(v.y()) + ", " + format_value(v.z()) + ")";
}

void require_finite(const std::string& field, double value) {
  if (!std::isfinite(value)) {
    throw InvalidArgument(field + " must be finite, got " + format_value(value));
  }
}

void require_finite(const std::string& field, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    throw InvalidArgument(field + " must be finite, got " + format_vector(v));
  }
}

void require_positive(const std::string& field, double value) {
  require_finite(field, value);
  if (!(value > 0.0)) {
    throw InvalidArgument(field + " must be positive, got " + format_value(value));
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
    throw InvalidArgument(field + " must be finite, got " + text());
  }
  double norm = c.norm();
  // Huge finite coefficients overflow the plain norm (giving a zero quaternion); scale instead.
  if (std::isinf(norm)) norm = c.stableNorm();
  if (!(norm > 1e-9)) {
    throw InvalidArgument(field + " must be a non-zero quaternion, got " + text());
  }
  return Eigen::Quaterniond(c / norm);
}

}  // namespace virtual_go
