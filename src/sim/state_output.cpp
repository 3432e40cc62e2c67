#include "virtual_go/sim/state_output.h"

#include <cmath>

#include "virtual_go/common/validation.h"
#include "virtual_go/geometry/rotation.h"

namespace virtual_go {
namespace {

void require_output(const char* name, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    throw IntegrationError(std::string("the state's ") + name + " " + format_vector(v) +
                           " is not finite, so it cannot be published");
  }
}

}  // namespace

StateOutput state_output(const MotionModel& model, const RigidBodyState& state) {
  StateOutput out;
  out.position_world = state.position_world;
  out.orientation = state.orientation;
  out.velocity_world = state.velocity_world;
  out.angular_momentum_world = state.angular_momentum_world;
  require_output("position", out.position_world);
  if (!out.orientation.coeffs().allFinite() ||
      !(std::abs(out.orientation.squaredNorm() - 1.0) <= 1e-9)) {
    throw IntegrationError(
        "the state's orientation is not a unit quaternion, so it cannot be "
        "published");
  }
  require_output("velocity", out.velocity_world);
  require_output("angular momentum", out.angular_momentum_world);
  out.angular_velocity_world =
      model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  require_output("angular velocity", out.angular_velocity_world);
  const Eigen::Quaterniond to_body = state.orientation.conjugate();
  out.velocity_body = rotate_without_overflow(to_body, state.velocity_world);
  require_output("velocity in the stone frame", out.velocity_body);
  out.angular_velocity_body = rotate_without_overflow(to_body, out.angular_velocity_world);
  require_output("angular velocity in the stone frame", out.angular_velocity_body);
  return out;
}

}  // namespace virtual_go
