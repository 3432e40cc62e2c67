// Private helper of euler and rk4: refuse a step that rotates further than the integrator can
// follow (its registry entry's max_rotation_per_step), naming the integrators that can.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {

inline void check_rotation_per_step(const Integrator& integrator, double dt_s, double omega_norm) {
  const double max_rotation = integrator.max_rotation_per_step();
  if (dt_s * omega_norm > max_rotation) {
    std::vector<std::string> any_step;
    for (const IntegratorInfo& i : integrators().entries()) {
      if (std::isinf(i.max_rotation_per_step)) any_step.push_back(i.name);
    }
    throw IntegrationError(
        integrator.name() + " cannot keep up: dt * |omega| = " + format_value(dt_s * omega_norm) +
        " rad per step exceeds " + format_value(max_rotation) + " rad (dt " + format_value(dt_s) +
        " s, |omega| " + format_value(omega_norm) + " rad/s); use a smaller dt or the " +
        join(any_step, " or ") + " integrator");
  }
}

}  // namespace virtual_go
