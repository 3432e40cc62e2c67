// Explicit second-order Lie-Poisson splitting (McLachlan 1993; Touma & Wisdom 1994; Reich 1994):
// Strang composition of the exact flows of M_i^2 / 2 I_i, axes 1, 2, 3, 2, 1. Valid for any
// inertia; symplectic and reversible, world angular momentum exact, bounded energy error.
#pragma once

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class SplittingIntegrator : public Integrator {
 public:
  using Integrator::Integrator;

 protected:
  void step(RigidBodyState& state, double dt_s, FlightCache& cache) const override;
};

}  // namespace virtual_go
