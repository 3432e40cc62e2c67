// Where a lens touches a horizontal plane below it and how that point moves: the kinematics of
// sustained contact (docs/physics.md, "Sustained contact"). The contact point P is the lens point
// lowest along the world z axis; its offset r = P - x_G depends only on the symmetry axis
// b = R(q) e_z:
//   cap (sigma = +1 bottom, -1 top): r = sigma d b - R e_z             (P below the sphere centre)
//   rim:                             r = -a e, e = (e_z - b_z b) / |e_z - b_z b|  (lowest rim
//   point)
// Holding P on the plane fixes the height of G (z_G = h0 - r_z = h0 + rho(b_z)) and, since the
// gap rate is the normal velocity of the material point at P, the vertical velocity of G
// (v_z = -e_z . (omega x r)). Each part's formula is smooth and is used on its own side of the
// cap/rim switch (|b_z| = d/R); the two agree in position and slope at the switch.
#pragma once

#include <Eigen/Core>

#include "virtual_go/geometry/lens_geometry.h"

namespace virtual_go {

// Offset r = P - x_G (world, m) of the contact point on `part` for the world symmetry axis b
// (unit). For the rim b must not be vertical; for a cap the result is the cap's sphere point
// below its centre even beyond the cap's cone (the smooth continuation used between events).
Eigen::Vector3d plane_contact_offset_world(const LensGeometry& lens, LensPart part,
                                           const Eigen::Vector3d& axis_world);

// Rate of change dr/dt (m/s) of that offset when the stone turns at omega_world (rad/s). This
// is the motion of the contact point over the lens surface, not of a material point: on a cap
// it is sigma d (omega x b); on the rim it also carries the point along the rim.
Eigen::Vector3d plane_contact_offset_rate_world(const LensGeometry& lens, LensPart part,
                                                const Eigen::Vector3d& axis_world,
                                                const Eigen::Vector3d& omega_world);

// Both at once (the rim's direction e is found once): what the right-hand side of sustained
// contact needs at every evaluation.
struct PlaneContactOffset {
  Eigen::Vector3d offset_world;       // r, m
  Eigen::Vector3d offset_rate_world;  // dr/dt, m/s
};
PlaneContactOffset plane_contact_offset_and_rate_world(const LensGeometry& lens, LensPart part,
                                                       const Eigen::Vector3d& axis_world,
                                                       const Eigen::Vector3d& omega_world);

// The part of the lens facing a horizontal plane below it, for the axis' world z component.
inline LensPart lens_part_on_plane(const LensGeometry& lens, double axis_z) {
  return lens.part_towards_plane(axis_z);
}

}  // namespace virtual_go
