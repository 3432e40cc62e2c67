#include "virtual_go/body/mass_properties.h"

#include <cmath>
#include <limits>
#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {

namespace {

// Positive, finite and normal: a subnormal value has fewer significant digits (a moment of
// 1e-310 kg m^2 keeps 11 of them, and w = L / I then comes back as 29.875 for 30).
void require_normal(const std::string& field, double value, const char* unit) {
  require_positive(field, value);
  if (value < std::numeric_limits<double>::min()) {
    throw InvalidArgument(field, field + " " + format_value(value) + " " + unit +
                                     " is below the smallest normal double " +
                                     format_value(std::numeric_limits<double>::min()) +
                                     ": too small to compute with");
  }
}

}  // namespace

MassProperties::MassProperties(double mass, const Eigen::Vector3d& principal_moments_body)
    : mass_(mass), moments_body_(principal_moments_body) {
  require_normal("mass", mass, "kg");
  require_normal("principal moment Ixx", principal_moments_body.x(), "kg m^2");
  require_normal("principal moment Iyy", principal_moments_body.y(), "kg m^2");
  require_normal("principal moment Izz", principal_moments_body.z(), "kg m^2");
}

MassProperties MassProperties::of_lens(const LensShape& shape, double density) {
  require_positive("density", density);
  const double a = shape.half_width(), c = shape.half_height();
  const double a2 = a * a, c2 = c * c;
  const double mass = density * shape.volume();
  // Closed forms (docs/physics.md, "The lens"): axial I3 and transverse I1 of a biconvex lens.
  const double i3 = M_PI * density * c * (10 * a2 * a2 + 5 * a2 * c2 + c2 * c2) / 30;
  const double i1 = M_PI * density * c * (10 * a2 * a2 + 15 * a2 * c2 + 7 * c2 * c2) / 60;
  return MassProperties(mass, Eigen::Vector3d(i1, i1, i3));
}

MassProperties MassProperties::of_lens_with_mass(const LensShape& shape, double mass) {
  require_positive("mass", mass);
  return of_lens(shape, mass / shape.volume());
}

bool MassProperties::is_axisymmetric() const {
  return std::abs(moments_body_.x() - moments_body_.y()) <=
         1e-12 * std::max(moments_body_.x(), moments_body_.y());
}

}  // namespace virtual_go
