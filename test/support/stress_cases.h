// Shared set-up of the stress suite: the size-33 slate stone, its tumble, and an independent
// closed form in long double (docs/physics.md, "Flight in closed form") to judge long runs by.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/go/stone.h"

namespace stress {

namespace vg = virtual_go;
using Vec3l = Eigen::Matrix<long double, 3, 1>;
using Quatl = Eigen::Quaternion<long double>;

inline vg::MassProperties slate33() {
  vg::StoneSpec spec;
  spec.size_number = 33;
  spec.material = "slate";
  return vg::make_stone(spec).mass_properties;
}

struct Case {
  vg::MotionSetup setup;
  vg::RigidBodyState initial;
};

// Thrown upwards, tilted (no body axis along a world axis), spinning with world omega.
inline Case make_case(const vg::MassProperties& mp, const Eigen::Vector3d& omega_world,
                      bool gravity = true,
                      vg::MotionModelKind kind = vg::MotionModelKind::rigid_body) {
  const vg::MotionModel model(kind, mp);
  vg::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0.0, 0.0, 0.5);
  s.velocity_world = Eigen::Vector3d(0.3, -0.2, 2.0);
  s.orientation = vg::rotation_exp(Eigen::Vector3d(0.3, -0.5, 0.7));
  return Case{vg::MotionSetup{model, gravity ? vg::kStandardGravity : Eigen::Vector3d::Zero()},
              vg::with_angular_velocity_world(model, s, omega_world)};
}

inline Case tumble() { return make_case(slate33(), Eigen::Vector3d(20.0, 5.0, 40.0)); }

inline Quatl exp_l(const Vec3l& v) {
  const long double angle = v.norm();
  if (angle == 0.0L) return Quatl::Identity();
  const long double s = std::sin(0.5L * angle) / angle;
  return Quatl(std::cos(0.5L * angle), s * v.x(), s * v.y(), s * v.z());
}

// q(t) = exp(t L / I1) q0 exp(-Omega t e_z), Omega = (I3 - I1) omega3 / I1, omega3 = L3_body / I3,
// evaluated in 64-bit-mantissa long double from the double inputs: at t ~ 1.7e5 s the phase
// t |L| / I1 ~ 7.5e6 rad carries ~1e-9 rad of round-off in double, ~4e-13 rad here.
inline Quatl closed_form_orientation(const vg::MassProperties& mp, const vg::RigidBodyState& s0,
                                     long double t) {
  const long double i1 = mp.principal_moments_body().x(), i3 = mp.principal_moments_body().z();
  const Quatl q0 = s0.orientation.normalized().cast<long double>();
  const Vec3l l = s0.angular_momentum_world.cast<long double>();
  const long double omega3 = (q0.conjugate() * l).z() / i3;
  const long double rate = (i3 - i1) * omega3 / i1;
  Quatl q = exp_l(l * (t / i1)) * q0 * exp_l(Vec3l(0.0L, 0.0L, -rate * t));
  q.normalize();
  return q;
}

inline long double orientation_error_l(const Quatl& ref, const Eigen::Quaterniond& q) {
  const Quatl d = ref.conjugate() * q.cast<long double>().normalized();
  return 2.0L * std::atan2(d.vec().norm(), std::fabs(d.w()));
}

inline bool unit_and_finite(const vg::RigidBodyState& s, double tolerance = 1e-12) {
  return s.position_world.allFinite() && s.velocity_world.allFinite() &&
         s.angular_momentum_world.allFinite() && s.orientation.coeffs().allFinite() &&
         std::abs(s.orientation.norm() - 1.0) < tolerance;
}

}  // namespace stress
