#include "virtual_go/world/world_config.h"

#include <cmath>

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"

namespace virtual_go {
namespace {

// Rebounds are cut at heights far below a stone's size; above this the cut-off would remove
// visible bounces.
constexpr double kMaxZenoHeightM = 1e-3;

}  // namespace

void validate_world_config(const WorldConfig& config) {
  require_finite("gravity", config.motion.gravity_world);
  ExactMotion probe(config.motion, RigidBodyState{});  // throws "inertia" without a closed form
  (void)probe;
  if (config.board_enabled) validate_board("board/size", config.board);
  validate_material("contact/board", config.board_material);
  validate_material("contact/table", config.table_material);
  validate_material("contact/stone", config.stone_material);
  const double h = config.zeno_height_m;
  if (!(h > 0.0 && h <= kMaxZenoHeightM)) {
    throw InvalidArgument("contact/zeno_height", "contact/zeno_height must be in (0, " +
                                                     format_value(kMaxZenoHeightM) + "] m, got " +
                                                     format_value(h));
  }
  const WorldOptions& o = config.options;
  require_positive("world/contact_search_horizon", o.contact_search_horizon_s);
  require_positive("world/lift_off_probe", o.lift_off_probe_s);
  validate_nonsmooth_options(o.nonsmooth);
}

}  // namespace virtual_go
