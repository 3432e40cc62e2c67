#include "virtual_go/common/validation.h"

#include <cmath>
#include <limits>

namespace virtual_go {
namespace {

[[noreturn]] void reject(std::string_view field, const std::string& complaint) {
  throw InvalidArgument(std::string(field), std::string(field) + complaint);
}

}  // namespace

void require_finite(std::string_view field, double value) {
  if (!std::isfinite(value)) {
    reject(field, " must be finite, got " + format_value(value));
  }
}

void require_finite(std::string_view field, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    reject(field, " must be finite, got " + format_vector(v));
  }
}

void require_positive(std::string_view field, double value) {
  require_finite(field, value);
  if (!(value > 0.0)) {
    reject(field, " must be positive, got " + format_value(value));
  }
}

double norm_without_overflow(const Eigen::Vector3d& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  // Squares of components in [1e-150, 1e150] neither overflow nor lose digits.
  if (!(largest > 0.0) || std::isinf(largest)) return largest;
  if (largest >= 1e-150 && largest <= 1e150) return v.norm();
  return largest * (v / largest).norm();
}

std::string norm_text(const Eigen::Vector3d& v) {
  const double norm = norm_without_overflow(v);
  if (std::isinf(norm) && v.allFinite()) {
    return "> " + format_value(std::numeric_limits<double>::max());
  }
  return "= " + format_value(norm);
}

Eigen::Quaterniond require_unit_quaternion(std::string_view field, const Eigen::Quaterniond& q) {
  const Eigen::Vector4d c = q.coeffs();
  // The message text is built only on failure: this check runs on every validated state.
  auto text = [&c] {
    return "(x " + format_value(c[0]) + ", y " + format_value(c[1]) + ", z " + format_value(c[2]) +
           ", w " + format_value(c[3]) + ")";
  };
  if (!c.allFinite()) {
    reject(field, " must be finite, got " + text());
  }
  const double norm = c.norm();
  if (std::isinf(norm) || !(norm > 1e-9)) {
    // Coefficients near the largest double overflow the sum of squares, and even a scaled
    // norm overflows when |q| itself exceeds the largest double (dividing by it would give a
    // zero quaternion); tiny ones (1e-200, denormals) underflow it. Divided by its largest
    // coefficient first, q has a norm in [1, 2]: any finite, non-zero size is normalised.
    const double largest = c.cwiseAbs().maxCoeff();
    if (!(largest > 0.0)) {
      reject(field, " must be a non-zero quaternion, got " + text());
    }
    const Eigen::Vector4d scaled = c / largest;
    return Eigen::Quaterniond(scaled / scaled.norm());
  }
  return Eigen::Quaterniond(c / norm);
}

}  // namespace virtual_go
