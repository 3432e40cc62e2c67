#include "virtual_go/flight/integrator_registry.h"

#include <limits>

#include "virtual_go/flight/euler_integrator.h"
#include "virtual_go/flight/exact_integrator.h"
#include "virtual_go/flight/rk4_integrator.h"
#include "virtual_go/flight/splitting_integrator.h"

namespace virtual_go {
namespace {

template <class T>
std::unique_ptr<Integrator> make(const IntegratorInfo& info, const MotionSetup& setup) {
  return std::make_unique<T>(info, setup);
}

constexpr double kAnyStep = std::numeric_limits<double>::infinity();

}  // namespace

const NameTable<IntegratorInfo>& integrators() {
  // euler and rk4 follow at most 1 rad per step (beyond it their error is no longer small, and
  // they refuse the step); splitting and exact take any step. Error constants: see
  // ErrorBoundConstants.
  // Two lines per integrator: name and summary; order p, step limit (rad), K_q K_E K_g, factory.
  // clang-format off
  static const NameTable<IntegratorInfo> table("integrator", "integrator", {
      {"euler", "the article's explicit Euler, first order",
       1, 1.0, {5.0, 0.5, 1.01}, &make<EulerIntegrator>},
      {"rk4", "classical fourth-order Runge-Kutta",
       4, 1.0, {0.1, 0.02, 0.0}, &make<Rk4Integrator>},
      {"splitting", "second-order symplectic Lie-Poisson splitting",
       2, kAnyStep, {2.0, 0.02, 0.0}, &make<SplittingIntegrator>},
      {"exact", "closed form (torque-free axisymmetric body)",
       0, kAnyStep, {0.0, 0.0, 0.0}, &make<ExactIntegrator>},
  });
  // clang-format on
  return table;
}

const IntegratorInfo* find_integrator(const std::string& name) { return integrators().find(name); }

std::vector<std::string> integrator_names() { return integrators().names(); }

std::unique_ptr<Integrator> make_integrator(const std::string& name, const MotionSetup& setup) {
  const IntegratorInfo& info = integrators().at(name);
  return info.make(info, setup);
}

}  // namespace virtual_go
