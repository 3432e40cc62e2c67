// Private helper: refuse a step that rotates further than an integrator can follow.
#pragma once

#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {

inline void check_rotation_per_step(const std::string& integrator, double dt, double omega_norm,
                                    double max_rotation) {
  if (dt * omega_norm > max_rotation) {
    throw IntegrationError(integrator +
                           " cannot keep up: dt * |omega| = " + format_value(dt * omega_norm) +
                           " rad per step exceeds " + format_value(max_rotation) + " rad (dt " +
                           format_value(dt) + " s, |omega| " + format_value(omega_norm) +
                           " rad/s); use a smaller dt or the splitting or exact integrator");
  }
}

}  // namespace virtual_go
