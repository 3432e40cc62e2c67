// Classical fourth-order Runge-Kutta on (x, v, q, L), then normalise q.
#pragma once

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class Rk4Integrator : public Integrator {
 public:
  using Integrator::Integrator;
  std::string name() const override { return "rk4"; }
  double max_rotation_per_step() const override { return 1.0; }

 protected:
  void step(RigidBodyState& state, double dt) override;
};

}  // namespace virtual_go
