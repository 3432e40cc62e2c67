#include "virtual_go/sim/stone_config.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/world/world.h"

namespace virtual_go {
namespace {

// The smallest value of a bound that has no other floor: positive, and normal.
constexpr double kMinBound = 1e-300;

[[noreturn]] void fail(const std::string& param, const std::string& problem) {
  throw ConfigError("~" + param, "~" + param + ": " + problem);
}

void require_positive_param(const std::string& param, double value, const std::string& unit) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    fail(param, "must be a positive finite number (" + unit + "), got " + format_value(value));
  }
}

void require_finite_param(const std::string& param, const Eigen::Vector3d& value) {
  if (!value.allFinite()) fail(param, "must be finite, got " + format_vector(value));
}

void check_frame(const std::string& param, const std::string& frame) {
  if (frame.empty()) fail(param, "must not be empty");
  // tf2 refuses frame ids with a leading slash.
  if (frame[0] == '/') fail(param, "must not start with '/', got " + quote_user_text(frame));
}

// A plausibility bound: within [lowest, highest] (the caps of stone_config.h).
void check_bound(const std::string& param, double value, double lowest, double highest,
                 const std::string& unit) {
  if (!(value >= lowest && value <= highest)) {  // also refuses NaN
    const std::string range =
        lowest == kMinBound ? "positive and at most " + format_limit(highest)
                            : "between " + format_limit(lowest) + " and " + format_limit(highest);
    fail(param, "must be " + range + " " + unit + ", got " + format_value(value));
  }
}

// A pair of bounds ~min_<quantity> < ~max_<quantity>, both within [lowest, highest].
void check_bound_pair(const std::string& quantity, double min, double max, double lowest,
                      double highest, const std::string& unit) {
  check_bound("min_" + quantity, min, lowest, highest, unit);
  check_bound("max_" + quantity, max, lowest, highest, unit);
  if (!(min < max)) {
    fail("max_" + quantity, "must be more than ~min_" + quantity + " " + format_value(min) + " " +
                                unit + ", got " + format_value(max) + " " + unit);
  }
}

// value within [~min_<name>, ~max_<name>].
void check_range(const std::string& param, double value, const std::string& what,
                 const std::string& bound_name, double lowest, double highest,
                 const std::string& unit) {
  if (!(value >= lowest && value <= highest)) {
    fail(param, what + " must be between ~min_" + bound_name + " " + format_value(lowest) +
                    " and ~max_" + bound_name + " " + format_value(highest) + " " + unit +
                    ", got " + format_value(value) + " " + unit);
  }
}

// The parameter behind each StoneSpec member, as make_stone's InvalidArgument::field() names it.
const std::string& stone_parameter(const std::string& spec_field) {
  static const std::map<std::string, std::string> parameters = {
      {"size_number", "stone/size"},  {"width", "stone/width"},     {"height", "stone/height"},
      {"material", "stone/material"}, {"density", "stone/density"}, {"mass", "stone/mass"}};
  return parameters.at(spec_field);
}

// A name from a table: the table's own error, under the parameter's name.
template <class Lookup>
auto named(const std::string& param, Lookup&& lookup) {
  try {
    return lookup();
  } catch (const InvalidArgument& e) {
    fail(param, e.what());
  }
}

void check_between(const std::string& param, double value, double lowest, double highest,
                   const std::string& unit) {
  if (!(value >= lowest && value <= highest)) {  // also refuses NaN
    fail(param, "must be between " + format_value(lowest) + " and " + format_value(highest) + unit +
                    ", got " + format_value(value));
  }
}

void check_material(const std::string& surface, const ContactMaterial& m) {
  const std::string prefix = "contact/" + surface + "/";
  check_between(prefix + "restitution", m.restitution, 0.0, 1.0, "");
  check_between(prefix + "friction", m.friction, 0.0, kMaxNodeFriction,
                " (a sliding lens meets Painleve's paradox near 0.99)");
  check_between(prefix + "rolling_resistance", m.rolling_resistance_m, 0.0,
                kMaxNodeRollingResistanceM, " m");
  check_between(prefix + "spinning_friction", m.spinning_friction_m, 0.0, kMaxNodeSpinningFrictionM,
                " m");
}

// A duration parameter on the dt grid: 0 = never, else longer than ~dt.
std::int64_t check_period(const std::string& param, double value_s, double dt_s,
                          std::int64_t dt_ns) {
  if (!std::isfinite(value_s) || value_s < 0.0 || value_s > kMaxAutoResetPeriodS) {
    fail(param, "must be between 0 (never) and " + format_value(kMaxAutoResetPeriodS) + " s, got " +
                    format_value(value_s));
  }
  const std::int64_t ns = round_to_ns(value_s);
  if (value_s > 0.0 && ns <= dt_ns) {
    fail(param, "must be 0 (never) or longer than ~dt " + format_value(dt_s) + " s, got " +
                    format_value(value_s) + " s");
  }
  return ns;
}

// ~real_time_factor: 0 (as fast as possible) or within its bounds, and only with ~publish_clock
// (without it ROS time sets the pace).
void check_real_time_factor(const StoneConfig& c) {
  const double f = c.real_time_factor;
  if (!(f == 0.0 || (f >= kMinRealTimeFactor && f <= kMaxRealTimeFactor))) {  // also NaN
    fail("real_time_factor", "must be 0 (as fast as possible) or between " +
                                 format_value(kMinRealTimeFactor) + " and " +
                                 format_value(kMaxRealTimeFactor) + ", got " + format_value(f));
  }
  if (!c.publish_clock && f != 1.0) {
    fail("real_time_factor",
         "needs ~publish_clock true (without it the simulation follows ROS time), got " +
             format_value(f));
  }
}

// The parameter behind a WorldConfig field the core names (validate_world_config, World).
std::string world_parameter(const std::string& field) {
  if (field == "state") return "initial/position";
  if (field == "inertia") return "model";
  if (field == "gravity") return "gravity";
  if (field.compare(0, 8, "contact/") == 0 || field == "board/size") return field;
  return "board/enabled";
}

// ~board/* and ~contact/* -> the world, checked, with the initial state clear of the board.
WorldConfig checked_world(const StoneConfig& c, const Stone& stone, const MotionSetup& setup,
                          const RigidBodyState& initial) {
  if (c.integrator != "exact") {
    fail("integrator",
         "must be 'exact' with ~board/enabled true (contacts are found on the "
         "closed-form flight), got " +
             quote_user_text(c.integrator));
  }
  WorldConfig world(setup, stone.shape);
  world.board_enabled = true;
  world.board.size_x_m = c.board_size_m.x();
  world.board.size_y_m = c.board_size_m.y();
  world.board.thickness_m = c.board_size_m.z();
  try {
    validate_board("~board/size", world.board);
  } catch (const InvalidArgument& e) {
    throw ConfigError("~board/size", e.what());
  }
  check_material("board", c.board_material);
  check_material("table", c.table_material);
  world.board_material = c.board_material;
  world.table_material = c.table_material;
  world.stone_contact = c.stone_contact;
  if (!(c.zeno_height_m > 0.0 && c.zeno_height_m <= kMaxNodeZenoHeightM)) {
    fail("contact/zeno_height", "must be positive and at most " +
                                    format_value(kMaxNodeZenoHeightM) + " m, got " +
                                    format_value(c.zeno_height_m));
  }
  world.zeno_height_m = c.zeno_height_m;
  // The World's own checks (a state overlapping the board or the table, a motion without a
  // closed form) under the parameter's name.
  try {
    const World probe(world, initial, 0.0);
  } catch (const InvalidArgument& e) {
    // Its message starts with the core's field name: say the parameter instead.
    std::string what = e.what();
    const std::string core_prefix = e.field() + ": ";
    if (what.compare(0, core_prefix.size(), core_prefix) == 0) what.erase(0, core_prefix.size());
    fail(world_parameter(e.field()), what);
  }
  return world;
}

}  // namespace

const std::vector<std::string>& stone_colors() {
  static const std::vector<std::string> colors{"black", "white"};
  return colors;
}

std::int64_t dt_to_ns(double dt_s) {
  require_positive_param("dt", dt_s, "s");
  const double ns = to_nanoseconds(dt_s);
  if (ns > 1e15) fail("dt", "is too large: " + format_value(dt_s) + " s");
  const double whole = std::round(ns);
  if (std::abs(ns - whole) > 1e-6) {
    fail("dt", "must be a whole number of nanoseconds (stamps are whole nanoseconds), got " +
                   format_value(dt_s) + " s = " + format_value(ns) + " ns; try " +
                   format_value(to_seconds(static_cast<std::int64_t>(whole))) + " s");
  }
  const auto dt_ns = static_cast<std::int64_t>(whole);
  if (dt_ns < kMinDtNs) {
    fail("dt", "must be at least " + format_value(to_seconds(kMinDtNs)) + " s, got " +
                   format_value(dt_s) + " s");
  }
  return dt_ns;
}

CheckedConfig check_config(const StoneConfig& c) {
  if (!(c.rate_hz >= kMinRateHz && c.rate_hz <= kMaxRateHz)) {  // also refuses NaN
    fail("rate", "must be between " + format_value(kMinRateHz) + " and " +
                     format_value(kMaxRateHz) + " Hz, got " + format_value(c.rate_hz));
  }
  const std::int64_t dt_ns = dt_to_ns(c.dt_s);
  const MotionModelKind model = named("model", [&] { return motion_model_from_name(c.model); });
  const IntegratorInfo* integrator =
      named("integrator", [&] { return &integrators().at(c.integrator); });
  // The bounds first: the checks below use them.
  check_bound("max_angular_velocity", c.max_angular_velocity, kMinBound, kMaxAngularVelocityCap,
              "rad/s");
  check_bound("max_speed", c.max_speed, kMinBound, kMaxSpeedCap, "m/s");
  check_bound("max_distance", c.max_distance, kMinBound, kMaxDistanceCap, "m");
  check_bound("max_gravity", c.max_gravity, kMinBound, kMaxGravityCap, "m/s^2");
  check_bound_pair("mass", c.min_mass, c.max_mass, kMinMassCap, kMaxMassCap, "kg");
  check_bound_pair("width", c.min_width, c.max_width, kMinWidthCap, kMaxWidthCap, "m");

  require_finite_param("gravity", c.gravity_world);
  if (!(norm_without_overflow(c.gravity_world) <= c.max_gravity)) {
    fail("gravity", "|g| " + norm_text(c.gravity_world) + " m/s^2 exceeds ~max_gravity " +
                        format_value(c.max_gravity) + " m/s^2");
  }
  check_range("stone/width", c.stone.width, "the width", "width", c.min_width, c.max_width, "m");
  if (c.stone.mass) {
    check_range("stone/mass", *c.stone.mass, "the mass", "mass", c.min_mass, c.max_mass, "kg");
  }
  // make_stone checks every field of the spec and names the one to blame; the message names
  // core fields, the parameter comes from field().
  std::optional<Stone> stone;
  try {
    stone = make_stone(c.stone);
  } catch (const InvalidArgument& e) {
    fail(stone_parameter(e.field()), e.what());
  }
  // A mass from the size and a density: blame what set it (the density, else the dimensions).
  const std::string mass_param = c.stone.density  ? "stone/density"
                                 : c.stone.height ? "stone/height"
                                                  : "stone/width";
  check_range(mass_param, stone->mass_properties.mass(),
              "the stone's mass (from its size and density)", "mass", c.min_mass, c.max_mass, "kg");
  const std::vector<std::string>& colors = stone_colors();
  if (std::find(colors.begin(), colors.end(), c.color) == colors.end()) {
    std::vector<std::string> quoted;
    for (const std::string& color : colors) quoted.push_back("'" + color + "'");
    fail("stone/color", "must be " + join(quoted, " or ") + ", got " + quote_user_text(c.color));
  }
  // A segment is reset at the first step at which its age reaches the period: one of ~dt or
  // less would reset the stone at every step, so it could never move.
  const std::int64_t auto_reset_ns =
      check_period("auto_reset_period", c.auto_reset_period_s, c.dt_s, dt_ns);
  const std::int64_t auto_reset_after_rest_ns =
      check_period("auto_reset_after_rest", c.auto_reset_after_rest_s, c.dt_s, dt_ns);
  check_real_time_factor(c);
  check_frame("world_frame", c.world_frame);
  check_frame("stone_frame", c.stone_frame);
  if (c.world_frame == c.stone_frame) {
    fail("stone_frame",
         "must differ from ~world_frame, both are " + quote_user_text(c.world_frame));
  }

  const MotionSetup setup{MotionModel(model, stone->mass_properties), c.gravity_world};
  const double dt_s = to_seconds(dt_ns);
  const RequestLimits limits{
      c.max_distance, c.max_speed,     c.max_angular_velocity, integrator->max_rotation_per_step,
      dt_s,           integrator->name};
  RigidBodyState initial;
  try {
    initial =
        state_from_request({"~initial/position", "~initial/orientation", "~initial/velocity",
                            "~initial/angular_velocity"},
                           setup.model, c.initial_position_world, c.initial_orientation_xyzw,
                           c.initial_velocity_world, c.initial_angular_velocity_world, limits);
  } catch (const InvalidArgument& e) {
    throw ConfigError(e.field(), e.what());
  }
  std::optional<WorldConfig> world;
  if (c.board_enabled) world = checked_world(c, *stone, setup, initial);
  return CheckedConfig{c,
                       *stone,
                       setup,
                       integrator,
                       dt_ns,
                       dt_s,
                       auto_reset_ns,
                       limits,
                       initial,
                       world,
                       auto_reset_after_rest_ns};
}

void validate_config(const StoneConfig& config) { check_config(config); }

}  // namespace virtual_go
