#include "virtual_go/sim/state_request.h"

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

void check_angular_velocity(const std::string& field, const Eigen::Vector3d& omega,
                            const AngularVelocityLimit& limit) {
  require_finite(field, omega);
  const double norm = omega.norm();
  if (norm > limit.max_angular_velocity) {
    throw InvalidArgument(field, field + ": |w| = " + format_value(norm) +
                                     " rad/s exceeds max_angular_velocity " +
                                     format_value(limit.max_angular_velocity) + " rad/s");
  }
  if (norm * limit.dt_s > limit.max_rotation_per_step) {
    throw InvalidArgument(
        field, field + ": |w| = " + format_value(norm) + " rad/s is too fast for the " +
                   limit.integrator + " integrator at dt " + format_value(limit.dt_s) +
                   " s (at most " + format_value(limit.max_rotation_per_step / limit.dt_s) +
                   " rad/s)");
  }
}

RequestFrame request_frame(const std::string& field, const std::string& frame,
                           const std::string& world_frame, const std::string& stone_frame) {
  if (frame.empty() || frame == "world" || frame == world_frame) return RequestFrame::world;
  if (frame == "stone" || frame == stone_frame) return RequestFrame::body;
  std::string known = "'world' or 'stone'";
  if (world_frame != "world" || stone_frame != "stone") {
    known += ", or the frame ids '" + world_frame + "' or '" + stone_frame + "'";
  }
  throw InvalidArgument(field, field + ": unknown frame '" + frame + "' (use " + known + ")");
}

RigidBodyState state_from_request(const StateFieldNames& fields, const MotionModel& model,
                                  const Eigen::Vector3d& position_world,
                                  const Eigen::Vector4d& orientation_xyzw,
                                  const Eigen::Vector3d& velocity_world,
                                  const Eigen::Vector3d& angular_velocity_world,
                                  const AngularVelocityLimit& limit) {
  require_finite(fields.position, position_world);
  const Eigen::Quaterniond orientation = require_unit_quaternion(
      fields.orientation, Eigen::Quaterniond(orientation_xyzw[3], orientation_xyzw[0],
                                             orientation_xyzw[1], orientation_xyzw[2]));
  require_finite(fields.velocity, velocity_world);
  check_angular_velocity(fields.angular_velocity, angular_velocity_world, limit);
  RigidBodyState state;
  state.position_world = position_world;
  state.orientation = orientation;
  state.velocity_world = velocity_world;
  return with_angular_velocity_world(model, state, angular_velocity_world).validated();
}

}  // namespace virtual_go
