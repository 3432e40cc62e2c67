// The Go stone's lens as contact geometry (docs/physics.md, "Contact geometry"): support points
// and its reach towards a plane, in the body frame (origin at the centre of mass G, z along the
// symmetry axis). The lens is the intersection of two spheres of radius R whose centres sit at +d
// e_z (the bottom cap, z <= 0) and -d e_z (the top cap, z >= 0); the caps meet at the rim, a circle
// of radius a at z = 0. Each cap's outward normals fill a cone of half-angle beta about -/+ e_z,
// cos beta = d / R.
#pragma once

#include <Eigen/Core>

#include "virtual_go/geometry/lens_shape.h"

namespace virtual_go {

// Which part of the lens a support point lies on.
enum class LensPart { bottom_cap, top_cap, rim };

class LensGeometry {
 public:
  explicit LensGeometry(const LensShape& shape);

  double half_width() const { return a_; }         // a, m: rim radius
  double half_height() const { return c_; }        // c, m: pole height above G
  double sphere_radius() const { return r_; }      // R, m
  double sphere_offset() const { return d_; }      // d = R - c, m: cap sphere centres at -/+ d e_z
  double cos_cap_cone() const { return d_ / r_; }  // cos beta: the cap/rim switch

  // The part of the lens whose outward normal is the unit body direction u: a cap when
  // |u_z| >= d/R (the switch is at d/R, not a/R), else the rim.
  LensPart part_facing(const Eigen::Vector3d& u_body) const;
  // Support point s(u) = argmax_{p in lens} u . p for a unit body direction u, body frame, m.
  Eigen::Vector3d support_body(const Eigen::Vector3d& u_body) const;

  // Reach rho(ct) of the lens along a unit direction n with ct = b . n, b the symmetry axis (all
  // in one frame): the largest distance of a lens point from G along -n, i.e. how far the lens
  // extends towards a plane below it with normal n. rho = R - d|ct| on a cap, a sqrt(1 - ct^2)
  // on the rim; C1 across the switch, |rho'| <= d. The gap of the lens above the plane
  // {p : n.p = h0} is n . x_G - h0 - rho(b . n).
  double reach(double ct) const;
  double reach_slope(double ct) const;      // d rho / d ct, m
  double reach_curvature(double ct) const;  // d^2 rho / d ct^2, m (0 on a cap)
  // The part facing a plane below with normal n (ct = b . n): bottom cap for ct >= d/R, top cap
  // for ct <= -d/R, else the rim.
  LensPart part_towards_plane(double ct) const;

 private:
  double a_, c_, r_, d_;
};

}  // namespace virtual_go
