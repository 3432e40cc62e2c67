#include "virtual_go/flight/exact_motion.h"

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/free_flight.h"
#include "virtual_go/geometry/rotation.h"

namespace virtual_go {

ExactMotion::ExactMotion(const MotionSetup& setup, const RigidBodyState& initial)
    : gravity_world_(setup.gravity_world), initial_(initial.validated()), body_rate_(0.0) {
  require_finite("gravity", setup.gravity_world);
  const MotionModel& model = setup.model;
  if (model.kind() == MotionModelKind::constant_omega) {
    left_rate_world_ =
        model.angular_velocity_world(initial_.orientation, initial_.angular_momentum_world);
    return;
  }
  const MassProperties& mp = model.mass_properties();
  if (!mp.is_axisymmetric()) {
    throw InvalidArgument(
        "inertia", "exact rigid_body motion needs an axisymmetric inertia (Ixx == Iyy), got " +
                       format_vector(mp.principal_moments_body()));
  }
  const double i1 = mp.principal_moments_body().x(), i3 = mp.principal_moments_body().z();
  left_rate_world_ = initial_.angular_momentum_world / i1;
  // omega3 = L3_body / I3 is constant; the body-frame precession rate follows from it.
  const double omega3 =
      (initial_.orientation.conjugate() * initial_.angular_momentum_world).z() / i3;
  body_rate_ = (i3 - i1) * omega3 / i1;
}

Eigen::Quaterniond ExactMotion::left_rotation(double h_s) const {
  return rotation_exp(h_s * left_rate_world_);
}

Eigen::Quaterniond ExactMotion::right_rotation(double h_s) const {
  return rotation_exp(Eigen::Vector3d(0.0, 0.0, -body_rate_ * h_s));
}

RigidBodyState ExactMotion::state_at(double t_s) const {
  require_finite("time", t_s);
  RigidBodyState s = initial_;
  free_flight(initial_, gravity_world_, true, t_s, s);
  s.orientation = left_rotation(t_s) * initial_.orientation * right_rotation(t_s);
  s.orientation.normalize();
  if (!s.position_world.allFinite() || !s.velocity_world.allFinite()) {
    // Finite but enormous t: the parabola overflows.
    throw InvalidArgument("time",
                          "time " + format_value(t_s) + " s is too large: the state overflows");
  }
  return s;
}

}  // namespace virtual_go
