// Closed-form stepping (docs/physics.md, "Exact stepping"): for a fixed dt a step is the exact
// translation and two precomputed quaternion products, q <- A q B. Every kReanchorSteps steps
// the state is re-evaluated from the closed form at n * dt, so the products' round-off never
// exceeds that of kReanchorSteps of them. What remains is the closed form's own: the rotation
// angle |w| t is a double, so the error grows as eps |w| t (about 2e-10 rad after 1e7 steps of
// 1/60 s at 45 rad/s). The anchor, step count and step rotations are the body's, in its
// FlightCache: the integrator itself keeps nothing between steps.
#pragma once

#include <cstdint>

#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class ExactIntegrator : public Integrator {
 public:
  static constexpr std::int64_t kReanchorSteps = 1024;

  // Throws InvalidArgument for a rigid_body model whose inertia is not axisymmetric.
  ExactIntegrator(const IntegratorInfo& info, const MotionSetup& setup);

 protected:
  void step(RigidBodyState& state, double dt_s, FlightCache& cache) const override;
};

}  // namespace virtual_go
