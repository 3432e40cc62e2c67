#include "virtual_go/world/world_body.h"

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {

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
