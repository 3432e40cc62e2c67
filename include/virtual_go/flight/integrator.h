// The interface of every flight integrator: one stateless object per motion setup advances any
// number of bodies; what it carries from one step of a body to the next lives in that body's
// FlightCache (flight_cache.h). The integrators and their facts are listed in
// integrator_registry.h.
#pragma once

#include <Eigen/Core>
#include <string>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

struct IntegratorInfo;
class FlightCache;

struct MotionSetup {
  MotionModel model;
  Eigen::Vector3d gravity_world;  // m/s^2, may be zero
};

class Integrator {
 public:
  // Throws InvalidArgument (field "gravity") for a non-finite gravity.
  Integrator(const IntegratorInfo& info, const MotionSetup& setup);
  virtual ~Integrator() = default;

  // The integrator's entry in the registry: name, order, step limit.
  const IntegratorInfo& info() const { return *info_; }
  const std::string& name() const;
  // Largest h * |omega| (rad) one step may take; infinity when any step is fine.
  double max_rotation_per_step() const;
  const MotionSetup& setup() const { return setup_; }

  // Advances one body's `state` by dt_s seconds (dt_s > 0, finite). `cache` belongs to that
  // body: pass the same one at every step, and call cache.invalidate() whenever the state was
  // replaced from outside (reset, teleport, impact). On error throws and leaves the state
  // unchanged: InvalidArgument (naming the field) for a non-finite state, a zero quaternion or
  // a bad dt, IntegrationError when the step cannot be taken. A finite, non-zero orientation
  // that is not unit is normalised first (as RigidBodyState::validated() does), so the step
  // starts from a rotation; the output quaternion is always unit.
  void advance(RigidBodyState& state, double dt_s, FlightCache& cache) const;
  // One step from `state` as given, with a fresh cache (for single steps and tests; `exact`
  // re-evaluates its closed form at every such call).
  void advance(RigidBodyState& state, double dt_s) const;

 protected:
  // `state` is finite with a unit quaternion; on return it may hold anything (advance checks).
  virtual void step(RigidBodyState& state, double dt_s, FlightCache& cache) const = 0;
  bool has_gravity() const { return has_gravity_; }
  // Exact translation under constant gravity: x += v h + g h^2 / 2, v += g h.
  void translate_exact(RigidBodyState& state, double dt_s) const;

 private:
  const IntegratorInfo* info_;
  MotionSetup setup_;
  bool has_gravity_;
};

}  // namespace virtual_go
