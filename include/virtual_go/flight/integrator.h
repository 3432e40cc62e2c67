// Integrators, chosen by name at run time; each works with both motion models.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

struct MotionSetup {
  MotionModel model;
  Eigen::Vector3d gravity_world;  // m/s^2, may be zero
};

class Integrator {
 public:
  explicit Integrator(const MotionSetup& setup);
  virtual ~Integrator() = default;

  virtual std::string name() const = 0;
  // Advances `state` by dt seconds (dt > 0, finite). On error throws and leaves state unchanged:
  // InvalidArgument (naming the field) for a non-finite state, a zero quaternion or a bad dt,
  // IntegrationError when the step cannot be taken. A finite, non-zero orientation that is not
  // unit is normalised first (as RigidBodyState::validated() does), so the step starts from a
  // rotation; the output quaternion is always unit.
  void advance(RigidBodyState& state, double dt);
  // Largest h * |omega| (rad) one step may take; infinity when any step is fine.
  virtual double max_rotation_per_step() const;

  const MotionSetup& setup() const { return setup_; }

 protected:
  virtual void step(RigidBodyState& state, double dt) = 0;
  bool has_gravity() const { return has_gravity_; }
  // Exact translation under constant gravity: x += v h + g h^2 / 2, v += g h.
  void translate_exact(RigidBodyState& state, double dt) const;

 private:
  MotionSetup setup_;
  bool has_gravity_;
};

// "euler", "rk4", "splitting", "exact"; throws InvalidArgument for anything else.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const MotionSetup& setup);
std::vector<std::string> integrator_names();

}  // namespace virtual_go
