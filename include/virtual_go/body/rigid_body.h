// A rigid body = mass properties + motion model + primary state. Every derived quantity
// (angular velocity, matrices, energy) is computed here and only here.
#pragma once

#include <Eigen/Geometry>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

const Eigen::Vector3d kStandardGravity(0.0, 0.0, -9.80665);  // m/s^2, world z up

class RigidBody {
 public:
  RigidBody(const MotionModel& model, const RigidBodyState& state);

  const RigidBodyState& state() const { return state_; }
  const MotionModel& model() const { return model_; }

  Eigen::Vector3d angular_velocity_world() const;
  Eigen::Vector3d angular_velocity_body() const;
  Eigen::Vector3d angular_momentum_world() const { return state_.angular_momentum_world; }

  // The article's RigidBodyMatrix / RigidBodyInverse: homogeneous body -> world and back.
  Eigen::Matrix4d body_to_world_matrix() const;
  Eigen::Matrix4d world_to_body_matrix() const;
  Eigen::Vector3d point_body_to_world(const Eigen::Vector3d& p_body) const;
  Eigen::Vector3d point_world_to_body(const Eigen::Vector3d& p_world) const;
  Eigen::Vector3d vector_body_to_world(const Eigen::Vector3d& v_body) const;
  Eigen::Vector3d vector_world_to_body(const Eigen::Vector3d& v_world) const;

  double translational_kinetic_energy() const;  // J
  double rotational_kinetic_energy() const;     // J, 1/2 omega . L
  double kinetic_energy() const;
  // -m g . x, zero at the world origin.
  double potential_energy(const Eigen::Vector3d& gravity_world) const;
  double total_energy(const Eigen::Vector3d& gravity_world) const;

 private:
  MotionModel model_;
  RigidBodyState state_;
};

// The energy of a body (J): kinetic 1/2 m v^2 + 1/2 omega . L plus the potential -m g . x (zero
// at the world origin). The one formula: RigidBody, the World, both contact models and every
// energy guard use it.
double body_energy(double mass_kg, const Eigen::Vector3d& position_world,
                   const Eigen::Vector3d& velocity_world,
                   const Eigen::Vector3d& angular_velocity_world,
                   const Eigen::Vector3d& angular_momentum_world,
                   const Eigen::Vector3d& gravity_world);
// The same for a state under its motion model.
double body_energy(const MotionModel& model, const RigidBodyState& state,
                   const Eigen::Vector3d& gravity_world);
// Its potential term, -m g . x (J): body_energy of the same state with v = L = 0, to the bit
// (its kinetic terms are then exactly zero and x - y is x + (-y)), without the rotation that
// turns L into omega.
double body_potential_energy(double mass_kg, const Eigen::Vector3d& position_world,
                             const Eigen::Vector3d& gravity_world);

// Sets the angular momentum so that the body's world angular velocity is omega_world.
RigidBodyState with_angular_velocity_world(const MotionModel& model, RigidBodyState state,
                                           const Eigen::Vector3d& omega_world);

}  // namespace virtual_go
