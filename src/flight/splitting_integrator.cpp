#include "virtual_go/flight/splitting_integrator.h"

#include <cmath>

#include "virtual_go/geometry/rotation.h"

namespace virtual_go {
namespace {

// Exact flow of M_i^2 / (2 I_i) over tau: the body spins about axis i at rate M_i / I_i.
// Body momentum rotates backwards, M <- Rot(e_i, -theta) M, orientation forwards, q <- q exp.
void axis_flow(int axis, double tau, double moment, Eigen::Vector3d& m_body,
               Eigen::Quaterniond& q) {
  const double theta = tau * m_body[axis] / moment;
  if (theta == 0.0) return;
  const double c = std::cos(theta), s = std::sin(theta);
  const int j = (axis + 1) % 3, k = (axis + 2) % 3;
  const double mj = m_body[j], mk = m_body[k];
  m_body[j] = c * mj + s * mk;
  m_body[k] = -s * mj + c * mk;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v[axis] = theta;
  q = q * rotation_exp(v);
}

}  // namespace

void SplittingIntegrator::step(RigidBodyState& state, double dt_s, FlightCache&) const {
  translate_exact(state, dt_s);
  if (state.angular_momentum_world.isZero(0.0)) return;

  const MotionModel& model = setup().model;
  if (model.kind() == MotionModelKind::constant_omega) {
    // Constant world omega: one exact rotation.
    state.orientation = rotation_exp(dt_s * model.angular_velocity_world(
                                                state.orientation, state.angular_momentum_world)) *
                        state.orientation;
    state.orientation.normalize();
    return;
  }
  // Each sub-flow conserves the world momentum R M, so L stays as it is; only q changes.
  const Eigen::Vector3d& inertia = model.mass_properties().principal_moments_body();
  Eigen::Vector3d m_body = state.orientation.conjugate() * state.angular_momentum_world;
  Eigen::Quaterniond q = state.orientation;
  axis_flow(0, 0.5 * dt_s, inertia[0], m_body, q);
  axis_flow(1, 0.5 * dt_s, inertia[1], m_body, q);
  axis_flow(2, dt_s, inertia[2], m_body, q);
  axis_flow(1, 0.5 * dt_s, inertia[1], m_body, q);
  axis_flow(0, 0.5 * dt_s, inertia[0], m_body, q);
  q.normalize();
  state.orientation = q;
}

}  // namespace virtual_go
