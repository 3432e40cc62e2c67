// Closed-form stepping: for a fixed dt a step is the exact translation and two precomputed
// quaternion products, q <- A q B. Every kReanchorSteps steps the state is re-evaluated from
// the closed form at n * dt, so the products' round-off never exceeds that of kReanchorSteps
// of them. What remains is the closed form's own: the rotation angle |w| t is a double, so
// the error grows as eps |w| t (about 2e-10 rad after 1e7 steps of 1/60 s at 45 rad/s).
#pragma once

#include <cstdint>
#include <optional>

#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class ExactIntegrator : public Integrator {
 public:
  static constexpr std::int64_t kReanchorSteps = 1024;

  // Throws InvalidArgument for a rigid_body model whose inertia is not axisymmetric.
  explicit ExactIntegrator(const MotionSetup& setup);
  std::string name() const override { return "exact"; }

 protected:
  void step(RigidBodyState& state, double dt) override;

 private:
  // Continues from the anchor only while the caller hands back our last output with the same dt.
  std::optional<ExactMotion> anchor_;
  RigidBodyState last_output_;
  double last_dt_ = 0.0;
  std::int64_t steps_since_anchor_ = 0;
  bool rotating_ = false;
  Eigen::Quaterniond left_step_ = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond right_step_ = Eigen::Quaterniond::Identity();
};

}  // namespace virtual_go
