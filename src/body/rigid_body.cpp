#include "virtual_go/body/rigid_body.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

RigidBody::RigidBody(const MotionModel& model, const RigidBodyState& state)
    : model_(model), state_(state.validated()) {}

Eigen::Vector3d RigidBody::angular_velocity_world() const {
  return model_.angular_velocity_world(state_.orientation, state_.angular_momentum_world);
}

Eigen::Vector3d RigidBody::angular_velocity_body() const {
  return state_.orientation.conjugate() * angular_velocity_world();
}

Eigen::Matrix4d RigidBody::body_to_world_matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = state_.orientation.toRotationMatrix();
  m.topRightCorner<3, 1>() = state_.position_world;
  return m;
}

Eigen::Matrix4d RigidBody::world_to_body_matrix() const {
  // Inverse of [R x; 0 1] is [R^T -R^T x; 0 1]: no general 4x4 inversion needed.
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d rt = state_.orientation.toRotationMatrix().transpose();
  m.topLeftCorner<3, 3>() = rt;
  m.topRightCorner<3, 1>() = -rt * state_.position_world;
  return m;
}

Eigen::Vector3d RigidBody::point_body_to_world(const Eigen::Vector3d& p_body) const {
  return state_.orientation * p_body + state_.position_world;
}

Eigen::Vector3d RigidBody::point_world_to_body(const Eigen::Vector3d& p_world) const {
  return state_.orientation.conjugate() * (p_world - state_.position_world);
}

Eigen::Vector3d RigidBody::vector_body_to_world(const Eigen::Vector3d& v_body) const {
  return state_.orientation * v_body;
}

Eigen::Vector3d RigidBody::vector_world_to_body(const Eigen::Vector3d& v_world) const {
  return state_.orientation.conjugate() * v_world;
}

double RigidBody::translational_kinetic_energy() const {
  return 0.5 * model_.mass_properties().mass() * state_.velocity_world.squaredNorm();
}

double RigidBody::rotational_kinetic_energy() const {
  return 0.5 * angular_velocity_world().dot(state_.angular_momentum_world);
}

double RigidBody::kinetic_energy() const {
  return translational_kinetic_energy() + rotational_kinetic_energy();
}

double RigidBody::potential_energy(const Eigen::Vector3d& gravity_world) const {
  return -model_.mass_properties().mass() * gravity_world.dot(state_.position_world);
}

double RigidBody::total_energy(const Eigen::Vector3d& gravity_world) const {
  return body_energy(model_, state_, gravity_world);
}

double body_energy(double mass_kg, const Eigen::Vector3d& position_world,
                   const Eigen::Vector3d& velocity_world,
                   const Eigen::Vector3d& angular_velocity_world,
                   const Eigen::Vector3d& angular_momentum_world,
                   const Eigen::Vector3d& gravity_world) {
  return 0.5 * mass_kg * velocity_world.squaredNorm() +
         0.5 * angular_velocity_world.dot(angular_momentum_world) +
         body_potential_energy(mass_kg, position_world, gravity_world);
}

double body_potential_energy(double mass_kg, const Eigen::Vector3d& position_world,
                             const Eigen::Vector3d& gravity_world) {
  return -(mass_kg * gravity_world.dot(position_world));
}

double body_energy(const MotionModel& model, const RigidBodyState& state,
                   const Eigen::Vector3d& gravity_world) {
  return body_energy(model.mass_properties().mass(), state.position_world, state.velocity_world,
                     model.angular_velocity_world(state.orientation, state.angular_momentum_world),
                     state.angular_momentum_world, gravity_world);
}

RigidBodyState with_angular_velocity_world(const MotionModel& model, RigidBodyState state,
                                           const Eigen::Vector3d& omega_world) {
  state = state.validated();
  require_finite("angular velocity", omega_world);
  state.angular_momentum_world = model.angular_momentum_world(state.orientation, omega_world);
  // A finite but absurd omega (or inertia) can overflow L; never hand back a non-finite state.
  // The input to blame is the angular velocity.
  if (!state.angular_momentum_world.allFinite()) {
    throw InvalidArgument("angular velocity", "angular momentum from angular velocity " +
                                                  format_vector(omega_world) +
                                                  " must be finite, got " +
                                                  format_vector(state.angular_momentum_world));
  }
  return state;
}

}  // namespace virtual_go
