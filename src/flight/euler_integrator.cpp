#include "virtual_go/flight/euler_integrator.h"

#include "step_limit.h"

namespace virtual_go {

void EulerIntegrator::step(RigidBodyState& state, double dt_s, FlightCache&) const {
  // The article's order: velocity first, then position with the new velocity.
  if (has_gravity()) state.velocity_world += dt_s * setup().gravity_world;
  state.position_world += dt_s * state.velocity_world;

  if (state.angular_momentum_world.isZero(0.0)) return;
  const Eigen::Vector3d omega =
      setup().model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  check_rotation_per_step(*this, dt_s, omega.norm());
  const Eigen::Quaterniond spin(0.0, omega.x(), omega.y(), omega.z());
  state.orientation.coeffs() += (0.5 * dt_s) * (spin * state.orientation).coeffs();
  state.orientation.normalize();
}

}  // namespace virtual_go
