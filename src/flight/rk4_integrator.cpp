#include "virtual_go/flight/rk4_integrator.h"

#include "step_limit.h"

namespace virtual_go {

void Rk4Integrator::step(RigidBodyState& state, double dt_s, FlightCache&) const {
  // Constant acceleration: RK4 reproduces the exact parabola, so translate in closed form.
  translate_exact(state, dt_s);
  if (state.angular_momentum_world.isZero(0.0)) return;

  const MotionModel& model = setup().model;
  const Eigen::Vector3d& l_world = state.angular_momentum_world;  // no torque: constant
  check_rotation_per_step(*this, dt_s,
                          model.angular_velocity_world(state.orientation, l_world).norm());
  // dq/dt = 1/2 (0, omega(q)) q, with omega from the normalised stage orientation.
  auto derivative = [&](const Eigen::Vector4d& q) -> Eigen::Vector4d {
    const Eigen::Quaterniond qq(q);
    const Eigen::Vector3d w = model.angular_velocity_world(qq.normalized(), l_world);
    return 0.5 * (Eigen::Quaterniond(0.0, w.x(), w.y(), w.z()) * qq).coeffs();
  };
  const Eigen::Vector4d q0 = state.orientation.coeffs();
  const Eigen::Vector4d k1 = derivative(q0);
  const Eigen::Vector4d k2 = derivative(q0 + 0.5 * dt_s * k1);
  const Eigen::Vector4d k3 = derivative(q0 + 0.5 * dt_s * k2);
  const Eigen::Vector4d k4 = derivative(q0 + dt_s * k3);
  state.orientation.coeffs() = q0 + (dt_s / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  state.orientation.normalize();
}

}  // namespace virtual_go
