#include "virtual_go/contact/impact.h"

#include <algorithm>

#include "impulse_process.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

Eigen::Matrix3d impulse_response_world(const MotionModel& model,
                                       const Eigen::Quaterniond& orientation,
                                       const Eigen::Vector3d& r) {
  const MassProperties& mp = model.mass_properties();
  Eigen::Matrix3d inverse_inertia;
  if (model.kind() == MotionModelKind::constant_omega) {
    inverse_inertia = Eigen::Matrix3d::Identity() / model.isotropic_moment();
  } else {
    const Eigen::Matrix3d rot = orientation.toRotationMatrix();
    inverse_inertia = rot * mp.inverse_inertia_body() * rot.transpose();
  }
  const Eigen::Matrix3d rx = impulse_process::cross_matrix(r);
  Eigen::Matrix3d k = Eigen::Matrix3d::Identity() / mp.mass() - rx * inverse_inertia * rx;
  return 0.5 * (k + k.transpose());  // exactly symmetric
}

Impact resolve_impact(const MotionModel& model, const RigidBodyState& before,
                      const Eigen::Vector3d& contact_point_world,
                      const Eigen::Vector3d& normal_world, const ContactMaterial& material,
                      const Eigen::Vector3d& gravity_world, const ImpactOptions& options) {
  const RigidBodyState state = before.validated();
  require_finite("contact point", contact_point_world);
  require_finite("contact normal", normal_world);
  require_finite("gravity", gravity_world);
  validate_material("material", material);
  require_positive("impact zeno_height", options.zeno_height_m);
  require_positive("impact tolerance", options.tolerance);
  const double normal_length = normal_world.norm();
  if (!(normal_length > 0.0)) {
    throw InvalidArgument("normal_world",
                          "contact normal must be non-zero, got " + format_vector(normal_world));
  }
  const Eigen::Vector3d n = normal_world / normal_length;
  const Eigen::Vector3d r = contact_point_world - state.position_world;
  const double mass = model.mass_properties().mass();

  Impact result;
  result.state = state;
  const Eigen::Vector3d omega =
      model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  const Eigen::Vector3d u = state.velocity_world + omega.cross(r);
  result.contact_velocity_before_world = u;
  result.contact_velocity_after_world = u;
  result.normal_velocity_before_mps = result.normal_velocity_after_mps = u.dot(n);
  const Eigen::Matrix3d k_world = impulse_response_world(model, state.orientation, r);
  const impulse_process::ContactFrame frame = impulse_process::contact_frame(u, n, k_world);
  if (!frame.approaching) {
    result.separating = true;
    return result;
  }

  impulse_process::ImpulseProcess process(frame.k_scaled, frame.u_scaled, material.friction,
                                          material.restitution, options);
  process.run();
  Eigen::Vector3d pc = frame.impulse_scale * process.impulse();
  bool stuck = process.stuck();
  // Zeno cut-off: a rebound lower than h_min ends the bouncing; the contact becomes sustained.
  const double g_n = -gravity_world.dot(n);
  const double un_after = (frame.u + frame.k * pc).z();
  if (g_n > 0.0 && un_after * un_after < 2.0 * g_n * options.zeno_height_m) {
    pc = frame.impulse_scale * process.compression_impulse();
    stuck = process.stuck_at_compression();
    result.sustained = true;
  }
  pc *= impulse_process::energy_safe_scale(pc, frame.u, frame.k);

  const Eigen::Vector3d impulse = frame.basis * pc;
  result.impulse_world = impulse;
  result.energy_change_j = impulse.dot(u) + 0.5 * impulse.dot(k_world * impulse);
  result.compression_impulse_ns = frame.impulse_scale * process.compression_impulse().z();
  result.normal_impulse_ns = pc.z();
  result.state.velocity_world = state.velocity_world + impulse / mass;
  result.state.angular_momentum_world = state.angular_momentum_world + r.cross(impulse);
  const Eigen::Vector3d omega_after =
      model.angular_velocity_world(result.state.orientation, result.state.angular_momentum_world);
  result.contact_velocity_after_world = result.state.velocity_world + omega_after.cross(r);
  result.normal_velocity_after_mps = result.contact_velocity_after_world.dot(n);
  result.stuck = stuck;
  result.slip_steps = process.steps();
  result.straight_slip = process.straight_slip();
  result.frictionless_fallback = process.frictionless_fallback();
  return result;
}

}  // namespace virtual_go
