#include "virtual_go/contact/pair_impact.h"

#include "impulse_process.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

namespace {

// The state's validated copy; an InvalidArgument names the stone ("a/velocity").
RigidBodyState validated(const char* stone, const RigidBodyState& state) {
  try {
    return state.validated();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string(stone) + "/" + e.field(), e.what());
  }
}

Eigen::Vector3d contact_velocity(const MotionModel& model, const RigidBodyState& state,
                                 const Eigen::Vector3d& r) {
  return state.velocity_world +
         model.angular_velocity_world(state.orientation, state.angular_momentum_world).cross(r);
}

}  // namespace

PairImpact resolve_pair_impact(const MotionModel& model_a, const RigidBodyState& before_a,
                               const MotionModel& model_b, const RigidBodyState& before_b,
                               const Eigen::Vector3d& contact_point_world,
                               const Eigen::Vector3d& normal_world, const ContactMaterial& material,
                               const ImpactOptions& options) {
  const RigidBodyState a = validated("a", before_a), b = validated("b", before_b);
  require_finite("contact point", contact_point_world);
  require_finite("contact normal", normal_world);
  validate_material("material", material);
  require_positive("impact tolerance", options.tolerance);
  const double normal_length = normal_world.norm();
  if (!(normal_length > 0.0)) {
    throw InvalidArgument("normal_world",
                          "contact normal must be non-zero, got " + format_vector(normal_world));
  }
  const Eigen::Vector3d n = normal_world / normal_length;
  const Eigen::Vector3d r_a = contact_point_world - a.position_world;
  const Eigen::Vector3d r_b = contact_point_world - b.position_world;

  PairImpact result;
  result.state_a = a;
  result.state_b = b;
  const Eigen::Vector3d u = contact_velocity(model_b, b, r_b) - contact_velocity(model_a, a, r_a);
  result.contact_velocity_before_world = result.contact_velocity_after_world = u;
  result.normal_velocity_before_mps = result.normal_velocity_after_mps = u.dot(n);
  const Eigen::Matrix3d k_world = impulse_response_world(model_a, a.orientation, r_a) +
                                  impulse_response_world(model_b, b.orientation, r_b);
  const impulse_process::ContactFrame frame = impulse_process::contact_frame(u, n, k_world);
  if (!frame.approaching) {
    result.separating = true;
    return result;
  }

  impulse_process::ImpulseProcess process(frame.k_scaled, frame.u_scaled, material.friction,
                                          material.restitution, options);
  process.run();
  Eigen::Vector3d pc = frame.impulse_scale * process.impulse();
  pc *= impulse_process::energy_safe_scale(pc, frame.u, frame.k);

  const Eigen::Vector3d impulse = frame.basis * pc;
  result.impulse_world = impulse;
  result.energy_change_j = impulse.dot(u) + 0.5 * impulse.dot(k_world * impulse);
  result.compression_impulse_ns = frame.impulse_scale * process.compression_impulse().z();
  result.normal_impulse_ns = pc.z();
  const double mass_a = model_a.mass_properties().mass(), mass_b = model_b.mass_properties().mass();
  result.state_b.velocity_world = b.velocity_world + impulse / mass_b;
  result.state_b.angular_momentum_world = b.angular_momentum_world + r_b.cross(impulse);
  result.state_a.velocity_world = a.velocity_world - impulse / mass_a;
  result.state_a.angular_momentum_world = a.angular_momentum_world - r_a.cross(impulse);
  result.contact_velocity_after_world = contact_velocity(model_b, result.state_b, r_b) -
                                        contact_velocity(model_a, result.state_a, r_a);
  result.normal_velocity_after_mps = result.contact_velocity_after_world.dot(n);
  result.stuck = process.stuck();
  result.slip_steps = process.steps();
  result.straight_slip = process.straight_slip();
  result.frictionless_fallback = process.frictionless_fallback();
  return result;
}

}  // namespace virtual_go
