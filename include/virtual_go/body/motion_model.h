// How angular momentum maps to angular velocity: the article's constant world omega, or the
// physically accurate torque-free rigid body.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/common/name_table.h"

namespace virtual_go {

enum class MotionModelKind {
  // The article's model: world omega constant. Equivalent to a body with isotropic inertia
  // I_iso = trace(I) / 3 (so L = I_iso omega, and energy and L are conserved).
  constant_omega,
  // Torque-free rigid body with the stone's inertia tensor: L_world conserved,
  // omega_world = R I^-1 R^T L_world; an off-axis spin wobbles.
  rigid_body,
};

struct MotionModelInfo {
  std::string name;  // "constant_omega", "rigid_body"
  MotionModelKind kind;
};
// The models by name; an unknown name is an InvalidArgument (field "motion model").
const NameTable<MotionModelInfo>& motion_models();
MotionModelKind motion_model_from_name(const std::string& name);
std::string motion_model_name(MotionModelKind kind);

class MotionModel {
 public:
  MotionModel(MotionModelKind kind, const MassProperties& mass_properties);

  MotionModelKind kind() const { return kind_; }
  const MassProperties& mass_properties() const { return mass_properties_; }
  double isotropic_moment() const { return isotropic_moment_; }

  Eigen::Vector3d angular_velocity_world(const Eigen::Quaterniond& orientation,
                                         const Eigen::Vector3d& angular_momentum_world) const;
  Eigen::Vector3d angular_momentum_world(const Eigen::Quaterniond& orientation,
                                         const Eigen::Vector3d& angular_velocity_world) const;
  // World-frame inertia tensor R I R^T as this model sees it.
  Eigen::Matrix3d inertia_world(const Eigen::Quaterniond& orientation) const;

 private:
  MotionModelKind kind_;
  MassProperties mass_properties_;
  double isotropic_moment_;
};

}  // namespace virtual_go
