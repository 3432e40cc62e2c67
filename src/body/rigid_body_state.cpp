#include "virtual_go/body/rigid_body_state.h"

#include <cstring>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

bool same_bits(const double* a, const double* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}

}  // namespace

RigidBodyState RigidBodyState::validated() const {
  require_finite("position", position_world);
  require_finite("velocity", velocity_world);
  require_finite("angular momentum", angular_momentum_world);
  RigidBodyState s = *this;
  s.orientation = require_unit_quaternion("orientation", orientation);
  return s;
}

bool RigidBodyState::operator==(const RigidBodyState& other) const {
  // Member by member: the struct may have padding, whose bytes are not part of the state.
  return same_bits(position_world.data(), other.position_world.data(), 3) &&
         same_bits(orientation.coeffs().data(), other.orientation.coeffs().data(), 4) &&
         same_bits(velocity_world.data(), other.velocity_world.data(), 3) &&
         same_bits(angular_momentum_world.data(), other.angular_momentum_world.data(), 3);
}

}  // namespace virtual_go
