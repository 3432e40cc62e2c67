#include "virtual_go/sim/state_request.h"

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// "field: |v| = 2000 m/s exceeds ~max_speed 1000 m/s"
void check_norm(const std::string& field, const Eigen::Vector3d& v, const char* symbol,
                const char* unit, const char* limit_name, double limit) {
  require_finite(field, v);
  if (!(norm_without_overflow(v) <= limit)) {
    throw InvalidArgument(field, field + ": " + symbol + " " + norm_text(v) + " " + unit +
                                     " exceeds " + limit_name + " " + format_value(limit) + " " +
                                     unit);
  }
}

}  // namespace

void check_position(const std::string& field, const Eigen::Vector3d& position_world,
                    const RequestLimits& limits) {
  check_norm(field, position_world, "distance from the world origin", "m", "~max_distance",
             limits.max_distance);
}

void check_velocity(const std::string& field, const Eigen::Vector3d& velocity_world,
                    const RequestLimits& limits) {
  check_norm(field, velocity_world, "|v|", "m/s", "~max_speed", limits.max_speed);
}

void check_angular_velocity(const std::string& field, const Eigen::Vector3d& omega,
                            const RequestLimits& limits) {
  check_norm(field, omega, "|w|", "rad/s", "~max_angular_velocity", limits.max_angular_velocity);
  const double norm = omega.norm();  // at most max_angular_velocity by now: no overflow
  if (norm * limits.dt_s > limits.max_rotation_per_step) {
    throw InvalidArgument(
        field, field + ": |w| = " + format_value(norm) + " rad/s is too fast for the " +
                   limits.integrator + " integrator at dt " + format_value(limits.dt_s) +
                   " s (at most " + format_value(limits.max_rotation_per_step / limits.dt_s) +
                   " rad/s)");
  }
}

RequestFrame request_frame(const std::string& field, const std::string& frame,
                           const std::string& world_frame, const std::string& stone_frame) {
  if (frame.empty() || frame == "world" || frame == world_frame) return RequestFrame::world;
  if (frame == "stone" || frame == stone_frame) return RequestFrame::body;
  std::string known = "'world' or 'stone'";
  if (world_frame != "world" || stone_frame != "stone") {
    known += ", or the frame ids " + quote_user_text(world_frame) + " or " +
             quote_user_text(stone_frame);
  }
  throw InvalidArgument(
      field, field + ": unknown frame " + quote_user_text(frame) + " (use " + known + ")");
}

RigidBodyState state_from_request(const StateFieldNames& fields, const MotionModel& model,
                                  const Eigen::Vector3d& position_world,
                                  const Eigen::Vector4d& orientation_xyzw,
                                  const Eigen::Vector3d& velocity_world,
                                  const Eigen::Vector3d& angular_velocity_world,
                                  const RequestLimits& limits) {
  check_position(fields.position, position_world, limits);
  const Eigen::Quaterniond orientation = require_unit_quaternion(
      fields.orientation, Eigen::Quaterniond(orientation_xyzw[3], orientation_xyzw[0],
                                             orientation_xyzw[1], orientation_xyzw[2]));
  check_velocity(fields.velocity, velocity_world, limits);
  check_angular_velocity(fields.angular_velocity, angular_velocity_world, limits);
  RigidBodyState state;
  state.position_world = position_world;
  state.orientation = orientation;
  state.velocity_world = velocity_world;
  // Within the limits L = I w cannot overflow (stone_config.h, the caps); a refusal from here
  // would still name the request's field, not an internal one.
  try {
    return with_angular_velocity_world(model, state, angular_velocity_world).validated();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fields.angular_velocity, fields.angular_velocity + ": " + e.what());
  }
}

}  // namespace virtual_go
