// Classical fourth-order Runge-Kutta on (x, v, q, L), then normalise q.
#pragma once

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class Rk4Integrator : public Integrator {
 public:
  using Integrator::Integrator;

 protected:
  void step(RigidBodyState& state, double dt_s, FlightCache& cache) const override;
};

}  // namespace virtual_go
