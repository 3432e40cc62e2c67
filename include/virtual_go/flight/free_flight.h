// Translation under constant gravity in closed form, exact for any t: the one place the
// parabola is written (x = x0 + v0 t + g t^2 / 2, v = v0 + g t; docs/physics.md, "Flight in
// closed form").
#pragma once

#include <Eigen/Core>

#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

// Position and velocity of `to` become those of `from` after t_s seconds of free flight; `from`
// and `to` may be the same state. With has_gravity false the gravity terms are skipped (a
// scene without gravity does no gravity work).
inline void free_flight(const RigidBodyState& from, const Eigen::Vector3d& gravity_world,
                        bool has_gravity, double t_s, RigidBodyState& to) {
  // Position first: it needs the velocity at the start of the flight.
  if (has_gravity) {
    to.position_world =
        from.position_world + t_s * from.velocity_world + (0.5 * t_s * t_s) * gravity_world;
    to.velocity_world = from.velocity_world + t_s * gravity_world;
  } else {
    to.position_world = from.position_world + t_s * from.velocity_world;
    to.velocity_world = from.velocity_world;
  }
}

}  // namespace virtual_go
