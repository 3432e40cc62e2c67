#include "virtual_go/geometry/lens_shape.h"

#include <cmath>

#include "virtual_go/common/validation.h"

namespace virtual_go {

LensShape::LensShape(double width, double height) : width_(width), height_(height) {
  require_positive("stone width", width);
  require_positive("stone height", height);
  if (!(height < width)) {
    throw InvalidArgument("stone height", "stone height must be less than the width " +
                                              format_value(width) + " m, got " +
                                              format_value(height) + " m");
  }
}

double LensShape::sphere_radius() const {
  const double a = half_width(), c = half_height();
  return (a * a + c * c) / (2 * c);
}

double LensShape::sphere_center_offset() const { return sphere_radius() - half_height(); }

double LensShape::volume() const {
  const double a = half_width(), c = half_height();
  return M_PI * c * (3 * a * a + c * c) / 3;
}

bool LensShape::contains(double x, double y, double z) const {
  const double r = sphere_radius(), d = sphere_center_offset();
  const double rho2 = x * x + y * y;
  // Inside both spheres: centred at -d (upper cap) and +d (lower cap).
  return rho2 + (z + d) * (z + d) <= r * r && rho2 + (z - d) * (z - d) <= r * r;
}

}  // namespace virtual_go
