#include "virtual_go/world/world_body.h"

#include <cmath>

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {

double point_speed_from_energy(const MotionModel& model, const LensGeometry& lens,
                               double kinetic_j) {
  const MassProperties& mass = model.mass_properties();
  const double smallest_moment = mass.principal_moments_body().minCoeff();
  const double a = lens.half_width();
  return std::sqrt(2.0 * kinetic_j * (1.0 / mass.mass() + a * a / smallest_moment));
}

WorldBody world_body(const StoneBody& body, MotionModelKind kind) {
  return WorldBody{MotionModel(kind, body.stone.mass_properties), body.stone.shape, body.color};
}

namespace {

MotionSetup checked_setup(const WorldBody& body, const Eigen::Vector3d& gravity_world) {
  require_finite("gravity", gravity_world);
  const MotionSetup setup{body.model, gravity_world};
  try {
    ExactMotion probe(setup, RigidBodyState{});  // throws "inertia" without a closed form
    (void)probe;
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("body/" + e.field(), e.what());
  }
  return setup;
}

}  // namespace

WorldBodyModel::WorldBodyModel(const WorldBody& body, const Eigen::Vector3d& gravity_world,
                               const BoardGeometry& board)
    : body_(body),
      setup_(checked_setup(body, gravity_world)),
      lens_(body.shape),
      board_(lens_, board),
      exact_(make_integrator("exact", setup_)) {}

}  // namespace virtual_go
