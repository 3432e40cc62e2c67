#include "virtual_go/body/rigid_body_state.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

RigidBodyState RigidBodyState::validated() const {
  require_finite("position", position_world);
  require_finite("velocity", velocity_world);
  require_finite("angular momentum", angular_momentum_world);
  RigidBodyState s = *this;
  s.orientation = require_unit_quaternion("orientation", orientation);
  return s;
}

bool RigidBodyState::operator==(const RigidBodyState& other) const {
  return position_world == other.position_world &&
         orientation.coeffs() == other.orientation.coeffs() &&
         velocity_world == other.velocity_world &&
         angular_momentum_world == other.angular_momentum_world;
}

}  // namespace virtual_go
