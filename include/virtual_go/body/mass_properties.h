// Mass and principal moments of inertia about the centre of mass, body frame.
#pragma once

#include <Eigen/Core>

#include "virtual_go/geometry/lens_shape.h"

namespace virtual_go {

class MassProperties {
 public:
  // mass in kg, principal moments (body x, y, z) in kg m^2; all positive and finite.
  MassProperties(double mass, const Eigen::Vector3d& principal_moments_body);

  // Solid lens of uniform density (kg/m^3), closed form.
  static MassProperties of_lens(const LensShape& shape, double density);
  // Solid lens with the given total mass (overrides density).
  static MassProperties of_lens_with_mass(const LensShape& shape, double mass);

  double mass() const { return mass_; }
  const Eigen::Vector3d& principal_moments_body() const { return moments_body_; }
  Eigen::Matrix3d inertia_body() const { return moments_body_.asDiagonal(); }
  Eigen::Matrix3d inverse_inertia_body() const { return moments_body_.cwiseInverse().asDiagonal(); }
  // I1 == I2 (to a relative 1e-12): the exact torque-free solution applies.
  bool is_axisymmetric() const;

 private:
  double mass_;
  Eigen::Vector3d moments_body_;
};

}  // namespace virtual_go
