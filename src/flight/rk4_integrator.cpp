#include "virtual_go/flight/rk4_integrator.h"

#include "step_limit.h"

namespace virtual_go {

void Rk4Integrator::step(RigidBodyState& state, double dt) {
  // Constant acceleration: RK4 reproduces the exact parabola, so translate in closed form.
  translate_exact(state, dt);
  if (state.angular_momentum_world.isZero(0.0)) return;

  const MotionModel& model = setup().model;
  const Eigen::Vector3d& l_world = state.angular_momentum_world;  // no torque: constant
  check_rotation_per_step(name(), dt,
                          model.angular_velocity_world(state.orientation, l_world).norm(),
                          max_rotation_per_step());
  // dq/dt = 1/2 (0, omega(q)) q, with omega from the normalised stage orientation.
  auto derivative = [&](const Eigen::Vector4d& q) -> Eigen::Vector4d {
    const Eigen::Quaterniond qq(q);
    const Eigen::Vector3d w = model.angular_velocity_world(qq.normalized(), l_world);
    return 0.5 * (Eigen::Quaterniond(0.0, w.x(), w.y(), w.z()) * qq).coeffs();
  };
  const Eigen::Vector4d q0 = state.orientation.coeffs();
  const Eigen::Vector4d k1 = derivative(q0);
  const Eigen::Vector4d k2 = derivative(q0 + 0.5 * dt * k1);
  const Eigen::Vector4d k3 = derivative(q0 + 0.5 * dt * k2);
  const Eigen::Vector4d k4 = derivative(q0 + dt * k3);
  state.orientation.coeffs() = q0 + (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  state.orientation.normalize();
}

}  // namespace virtual_go
