#include "virtual_go/geometry/lens_geometry.h"

#include <cmath>

namespace virtual_go {

LensGeometry::LensGeometry(const LensShape& shape)
    : a_(shape.half_width()),
      c_(shape.half_height()),
      r_(shape.sphere_radius()),
      d_(shape.sphere_center_offset()) {}

LensPart LensGeometry::part_facing(const Eigen::Vector3d& u_body) const {
  if (u_body.z() <= -cos_cap_cone()) return LensPart::bottom_cap;
  if (u_body.z() >= cos_cap_cone()) return LensPart::top_cap;
  return LensPart::rim;
}

Eigen::Vector3d LensGeometry::support_body(const Eigen::Vector3d& u_body) const {
  switch (part_facing(u_body)) {
    case LensPart::bottom_cap:  // sphere centred at +d e_z
      return Eigen::Vector3d(0.0, 0.0, d_) + r_ * u_body;
    case LensPart::top_cap:  // sphere centred at -d e_z
      return Eigen::Vector3d(0.0, 0.0, -d_) + r_ * u_body;
    case LensPart::rim:
    default: {
      const double xy = std::hypot(u_body.x(), u_body.y());
      return Eigen::Vector3d(a_ * u_body.x() / xy, a_ * u_body.y() / xy, 0.0);
    }
  }
}

LensPart LensGeometry::part_towards_plane(double ct) const {
  // The plane lies along -n: the facing part has outward normal -n, body z component -ct.
  if (ct >= cos_cap_cone()) return LensPart::bottom_cap;
  if (ct <= -cos_cap_cone()) return LensPart::top_cap;
  return LensPart::rim;
}

double LensGeometry::reach(double ct) const {
  const double act = std::abs(ct);
  if (act >= cos_cap_cone()) return r_ - d_ * act;
  return a_ * std::sqrt(std::max(0.0, 1.0 - ct * ct));
}

double LensGeometry::reach_slope(double ct) const {
  if (ct >= cos_cap_cone()) return -d_;
  if (ct <= -cos_cap_cone()) return d_;
  return -a_ * ct / std::sqrt(1.0 - ct * ct);
}

double LensGeometry::reach_curvature(double ct) const {
  if (std::abs(ct) >= cos_cap_cone()) return 0.0;
  const double s2 = 1.0 - ct * ct;
  return -a_ / (s2 * std::sqrt(s2));
}

}  // namespace virtual_go
