#include "virtual_go/body/motion_model.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

const NameTable<MotionModelInfo>& motion_models() {
  static const NameTable<MotionModelInfo> table(
      "motion model", "motion model",
      {{"constant_omega", MotionModelKind::constant_omega},
       {"rigid_body", MotionModelKind::rigid_body}});
  return table;
}

MotionModelKind motion_model_from_name(const std::string& name) {
  return motion_models().at(name).kind;
}

std::string motion_model_name(MotionModelKind kind) {
  for (const MotionModelInfo& m : motion_models().entries()) {
    if (m.kind == kind) return m.name;
  }
  return "unknown";  // not reached: every kind has an entry
}

MotionModel::MotionModel(MotionModelKind kind, const MassProperties& mass_properties)
    : kind_(kind),
      mass_properties_(mass_properties),
      isotropic_moment_(mass_properties.principal_moments_body().sum() / 3.0) {}

Eigen::Vector3d MotionModel::angular_velocity_world(
    const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_momentum_world) const {
  if (kind_ == MotionModelKind::constant_omega) return angular_momentum_world / isotropic_moment_;
  // omega = R I^-1 R^T L, with the diagonal body inverse inertia applied componentwise.
  const Eigen::Vector3d l_body = orientation.conjugate() * angular_momentum_world;
  return orientation *
         Eigen::Vector3d(l_body.cwiseQuotient(mass_properties_.principal_moments_body()));
}

Eigen::Vector3d MotionModel::angular_momentum_world(
    const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_velocity_world) const {
  if (kind_ == MotionModelKind::constant_omega) return isotropic_moment_ * angular_velocity_world;
  const Eigen::Vector3d w_body = orientation.conjugate() * angular_velocity_world;
  return orientation *
         Eigen::Vector3d(w_body.cwiseProduct(mass_properties_.principal_moments_body()));
}

Eigen::Matrix3d MotionModel::inertia_world(const Eigen::Quaterniond& orientation) const {
  if (kind_ == MotionModelKind::constant_omega) {
    return isotropic_moment_ * Eigen::Matrix3d::Identity();
  }
  const Eigen::Matrix3d r = orientation.toRotationMatrix();
  return r * mass_properties_.inertia_body() * r.transpose();
}

}  // namespace virtual_go
