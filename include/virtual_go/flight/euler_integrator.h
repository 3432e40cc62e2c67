// The article's explicit Euler: v += g h; x += v h; q += 1/2 (0, omega) q h; normalise.
// For rigid_body, omega is re-derived from L each step (as virtualgo does). First order.
#pragma once

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class EulerIntegrator : public Integrator {
 public:
  using Integrator::Integrator;

 protected:
  void step(RigidBodyState& state, double dt_s, FlightCache& cache) const override;
};

}  // namespace virtual_go
