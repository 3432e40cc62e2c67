#include "virtual_go/sim/stone_parameters.h"

#include <cmath>

#include "virtual_go/common/formatting.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/board.h"
#include "virtual_go/go/stone.h"

namespace virtual_go {
namespace {

// "a, b or c"
std::string one_of(const std::vector<std::string>& names) {
  if (names.size() < 2) return join(names, "");
  const std::vector<std::string> head(names.begin(), names.end() - 1);
  return join(head, ", ") + " or " + names.back();
}

// The size numbers with runs contracted: "22, 25, 28, 30-40".
std::string size_number_text() {
  const std::vector<int> sizes = size_numbers();
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < sizes.size();) {
    std::size_t j = i;
    while (j + 1 < sizes.size() && sizes[j + 1] == sizes[j] + 1) ++j;
    parts.push_back(j - i >= 2 ? std::to_string(sizes[i]) + "-" + std::to_string(sizes[j])
                               : std::to_string(sizes[i]));
    if (j - i == 1) parts.push_back(std::to_string(sizes[j]));
    i = j + 1;
  }
  return join(parts, ", ");
}

template <int N>
std::string list_text(const Eigen::Matrix<double, N, 1>& v) {
  std::vector<std::string> parts;
  for (int i = 0; i < N; ++i) parts.push_back(format_value(v[i]));
  return "[" + join(parts, ", ") + "]";
}

std::string value_text(const bool* v) { return *v ? "true" : "false"; }
std::string value_text(const double* v) { return format_value(*v); }
std::string value_text(const std::optional<double>* v) { return *v ? format_value(**v) : ""; }
std::string value_text(const std::optional<int>* v) { return *v ? std::to_string(**v) : ""; }
std::string value_text(const std::string* v) { return *v; }
std::string value_text(const Eigen::Vector3d* v) { return list_text(*v); }
std::string value_text(const Eigen::Vector4d* v) { return list_text(*v); }

// The grid the board's top face must hold: "19-line grid (0.396 x 0.4266 m)".
std::string grid_text() {
  const BoardGeometry b;
  // To 1e-6 m: (19 - 1) * 0.022 is 0.39599999999999996 in binary.
  auto mm_rounded = [](double m) { return format_value(std::round(m * 1e6) / 1e6); };
  return std::to_string(b.lines) + "-line grid (" + mm_rounded((b.lines - 1) * b.spacing_x_m) +
         " x " + mm_rounded((b.lines - 1) * b.spacing_y_m) + ")";
}

}  // namespace

std::vector<BoundParameter> bind_parameters(StoneConfig& c) {
  // The default of ~stone/size is make_stone's: the field itself is unset by default.
  const std::string default_size = std::to_string(kDefaultSizeNumber) + " = " +
                                   format_value(thickness_for_size(kDefaultSizeNumber) * 1e3) +
                                   " mm";
  return {
      {{"rate", "Hz", "",
        "publish rate, " + format_value(kMinRateHz) + " to " + format_value(kMaxRateHz)},
       &c.rate_hz},
      {{"dt", "s", "",
        "physics step, a whole number of nanoseconds, at least " + std::to_string(kMinDtNs) +
            " ns"},
       &c.dt_s},
      {{"model", "", "", one_of(motion_models().names())}, &c.model},
      {{"integrator", "", "", one_of(integrator_names())}, &c.integrator},
      {{"gravity", "m/s^2", "", "[x, y, z], world frame"}, &c.gravity_world},
      {{"stone/size", "", default_size,
        "Japanese size number " + size_number_text() + "; sets the height"},
       &c.stone.size_number},
      {{"stone/width", "m", "",
        "lens diameter, between ~min_width and ~max_width and more than the height"},
       &c.stone.width},
      {{"stone/height", "m", "", "lens thickness; overrides ~stone/size"}, &c.stone.height},
      {{"stone/material", "", "", one_of(material_names()) + "; sets the density"},
       &c.stone.material},
      {{"stone/density", "kg/m^3", "", "overrides the material"}, &c.stone.density},
      {{"stone/mass", "kg", "",
        "overrides density and material; the mass, given or not, between ~min_mass and "
        "~max_mass"},
       &c.stone.mass},
      {{"stone/color", "", "", one_of(stone_colors()) + " (the marker)"}, &c.color},
      {{"initial/position", "m", "", "[x, y, z], world frame"}, &c.initial_position_world},
      {{"initial/orientation", "", "", "[x, y, z, w], body -> world, normalised"},
       &c.initial_orientation_xyzw},
      {{"initial/velocity", "m/s", "", "[x, y, z], world frame"}, &c.initial_velocity_world},
      {{"initial/angular_velocity", "rad/s", "", "[x, y, z], world frame"},
       &c.initial_angular_velocity_world},
      // Plausibility bounds: a request or initial value beyond them is refused.
      {{"max_angular_velocity", "rad/s", "",
        "largest angular speed of a request or initial value; at most " +
            format_limit(kMaxAngularVelocityCap)},
       &c.max_angular_velocity},
      {{"max_speed", "m/s", "",
        "largest speed of a request or initial value; at most " + format_limit(kMaxSpeedCap) +
            " (light)"},
       &c.max_speed},
      {{"max_distance", "m", "",
        "largest distance from the world origin of a requested or initial position; at most " +
            format_limit(kMaxDistanceCap)},
       &c.max_distance},
      {{"max_gravity", "m/s^2", "",
        "largest magnitude of ~gravity; at most " + format_limit(kMaxGravityCap)},
       &c.max_gravity},
      {{"min_mass", "kg", "",
        "smallest stone mass, given or from size and density; at least " +
            format_limit(kMinMassCap)},
       &c.min_mass},
      {{"max_mass", "kg", "", "largest stone mass; at most " + format_limit(kMaxMassCap)},
       &c.max_mass},
      {{"min_width", "m", "", "smallest ~stone/width; at least " + format_limit(kMinWidthCap)},
       &c.min_width},
      {{"max_width", "m", "", "largest ~stone/width; at most " + format_limit(kMaxWidthCap)},
       &c.max_width},
      {{"auto_reset_period", "s", "",
        "reset when a segment is this old; 0 = never, else longer than ~dt and at most " +
            format_limit(kMaxAutoResetPeriodS)},
       &c.auto_reset_period_s},
      {{"auto_reset_after_rest", "s", "",
        "with the board: reset once the stone has rested this long; 0 = never, else longer "
        "than ~dt and at most " +
            format_limit(kMaxAutoResetPeriodS)},
       &c.auto_reset_after_rest_s},
      // The board and the contact laws (docs/physics.md, "World", "Contact materials").
      {{"board/enabled", "", "",
        "true: a Go board (top face at z = 0, centred on the origin) on a table; needs "
        "~integrator exact"},
       &c.board_enabled},
      {{"board/size", "m", "",
        "[x, y, thickness] of the board, each positive and at most " +
            format_value(kMaxBoardSizeM) + ", x and y at least the " + grid_text() +
            "; the table is at z = -thickness"},
       &c.board_size_m},
      {{"contact/board/restitution", "", "",
        "stone on board: Stronge's energetic coefficient e*, 0 to 1 (unmeasured placeholder)"},
       &c.board_material.restitution},
      {{"contact/board/friction", "", "",
        "stone on board: Coulomb mu, 0 to " + format_value(kMaxNodeFriction) +
            " (unmeasured placeholder)"},
       &c.board_material.friction},
      {{"contact/board/rolling_resistance", "m", "",
        "stone on board: rolling couple at most this times the normal force, 0 to " +
            format_value(kMaxNodeRollingResistanceM) + " (unmeasured placeholder)"},
       &c.board_material.rolling_resistance_m},
      {{"contact/board/spinning_friction", "m", "",
        "stone on board: spinning couple at most this times the normal force, 0 to " +
            format_value(kMaxNodeSpinningFrictionM) + " (unmeasured placeholder)"},
       &c.board_material.spinning_friction_m},
      {{"contact/table/restitution", "", "", "stone on table: as ~contact/board/restitution"},
       &c.table_material.restitution},
      {{"contact/table/friction", "", "", "stone on table: as ~contact/board/friction"},
       &c.table_material.friction},
      {{"contact/table/rolling_resistance", "m", "",
        "stone on table: as ~contact/board/rolling_resistance"},
       &c.table_material.rolling_resistance_m},
      {{"contact/table/spinning_friction", "m", "",
        "stone on table: as ~contact/board/spinning_friction"},
       &c.table_material.spinning_friction_m},
      {{"contact/stone/enabled", "", "",
        "true: stones touch, knock and rest against each other; false: they pass through "
        "each other"},
       &c.stone_contact},
      {{"contact/zeno_height", "m", "",
        "rebound height below which bouncing ends in sustained contact; positive and at most " +
            format_value(kMaxNodeZenoHeightM)},
       &c.zeno_height_m},
      {{"publish_clock", "", "",
        "true: the node owns the time: it publishes /clock (run other nodes with use_sim_time) "
        "and runs at ~real_time_factor times wall time"},
       &c.publish_clock},
      {{"real_time_factor", "", "",
        "with ~publish_clock: simulated s per wall s; 0 = as fast as possible, else " +
            format_value(kMinRealTimeFactor) + " to " + format_value(kMaxRealTimeFactor)},
       &c.real_time_factor},
      {{"world_frame", "", "", "tf frame of the world"}, &c.world_frame},
      {{"stone_frame", "", "", "tf frame of the stone (its body frame)"}, &c.stone_frame},
  };
}

const std::vector<ParameterInfo>& stone_parameters() {
  static const std::vector<ParameterInfo> parameters = [] {
    StoneConfig defaults;
    std::vector<ParameterInfo> out;
    for (BoundParameter& p : bind_parameters(defaults)) {
      if (p.info.default_text.empty()) {
        p.info.default_text = std::visit([](auto* field) { return value_text(field); }, p.field);
      }
      out.push_back(p.info);
    }
    return out;
  }();
  return parameters;
}

const ParameterInfo* find_parameter(const std::string& name) {
  for (const ParameterInfo& p : stone_parameters()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace virtual_go
