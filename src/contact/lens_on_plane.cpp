#include "virtual_go/contact/lens_on_plane.h"

#include <Eigen/Geometry>
#include <cmath>

namespace virtual_go {
namespace {

// The rim's lowest point is at -a e, e = w / |w|, w = e_z - b_z b: w and |w|.
Eigen::Vector3d rim_down_slope(const Eigen::Vector3d& axis_world, double& length) {
  const Eigen::Vector3d w = Eigen::Vector3d::UnitZ() - axis_world.z() * axis_world;
  length = w.norm();
  return w;
}

}  // namespace

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
      double length = 0.0;
      const Eigen::Vector3d w = rim_down_slope(axis_world, length);
      return -lens.half_width() * w / length;
    }
  }
}

Eigen::Vector3d plane_contact_offset_rate_world(const LensGeometry& lens, LensPart part,
                                                const Eigen::Vector3d& axis_world,
                                                const Eigen::Vector3d& omega_world) {
  return plane_contact_offset_and_rate_world(lens, part, axis_world, omega_world).offset_rate_world;
}

PlaneContactOffset plane_contact_offset_and_rate_world(const LensGeometry& lens, LensPart part,
                                                       const Eigen::Vector3d& axis_world,
                                                       const Eigen::Vector3d& omega_world) {
  const Eigen::Vector3d b_dot = omega_world.cross(axis_world);
  switch (part) {
    case LensPart::bottom_cap:
    case LensPart::top_cap: {
      // The offset's formula is plane_contact_offset_world's; its rate is sigma d (omega x b).
      const double sigma_d =
          part == LensPart::bottom_cap ? lens.sphere_offset() : -lens.sphere_offset();
      return {plane_contact_offset_world(lens, part, axis_world), sigma_d * b_dot};
    }
    case LensPart::rim:
    default: {
      // e = (e_z - c b) / s with c = b_z, s = |e_z - c b| = sqrt(1 - c^2):
      // de/dt = (-c_dot b - c b_dot) / s + e c c_dot / s^2.
      const double c = axis_world.z();
      const double c_dot = b_dot.z();
      double s = 0.0;
      const Eigen::Vector3d w = rim_down_slope(axis_world, s);
      const Eigen::Vector3d e = w / s;
      const Eigen::Vector3d e_dot =
          (-c_dot * axis_world - c * b_dot) / s + e * (c * c_dot / (s * s));
      return {-lens.half_width() * w / s, -lens.half_width() * e_dot};
    }
  }
}

}  // namespace virtual_go
