#include "virtual_go/contact/lens_on_plane.h"

#include <Eigen/Geometry>
#include <cmath>

namespace virtual_go {

Eigen::Vector3d plane_contact_offset_world(const LensGeometry& lens, LensPart part,
                                           const Eigen::Vector3d& axis_world) {
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  switch (part) {
    case LensPart::bottom_cap:
      return lens.sphere_offset() * axis_world - lens.sphere_radius() * ez;
    case LensPart::top_cap:
      return -lens.sphere_offset() * axis_world - lens.sphere_radius() * ez;
    case LensPart::rim:
    default: {
      const Eigen::Vector3d e = ez - axis_world.z() * axis_world;
      return -lens.half_width() * e / e.norm();
    }
  }
}

Eigen::Vector3d plane_contact_offset_rate_world(const LensGeometry& lens, LensPart part,
                                                const Eigen::Vector3d& axis_world,
                                                const Eigen::Vector3d& omega_world) {
  const Eigen::Vector3d b_dot = omega_world.cross(axis_world);
  switch (part) {
    case LensPart::bottom_cap:
      return lens.sphere_offset() * b_dot;
    case LensPart::top_cap:
      return -lens.sphere_offset() * b_dot;
    case LensPart::rim:
    default: {
      // e = (e_z - c b) / s with c = b_z, s = |e_z - c b| = sqrt(1 - c^2):
      // de/dt = (-c_dot b - c b_dot) / s + e c c_dot / s^2.
      const double c = axis_world.z();
      const double c_dot = b_dot.z();
      const Eigen::Vector3d w = Eigen::Vector3d::UnitZ() - c * axis_world;
      const double s = w.norm();
      const Eigen::Vector3d e = w / s;
      const Eigen::Vector3d e_dot =
          (-c_dot * axis_world - c * b_dot) / s + e * (c * c_dot / (s * s));
      return -lens.half_width() * e_dot;
    }
  }
}

}  // namespace virtual_go
