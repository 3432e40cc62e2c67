#include "virtual_go/sim/stone_config.h"

#include <cmath>

#include "virtual_go/flight/integrator.h"
#include "virtual_go/body/motion_model.h"

namespace virtual_go {
namespace {

[[noreturn]] void fail(const std::string& param, const std::string& problem) {
  throw ConfigError("~" + param + ": " + problem);
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
  if (frame[0] == '/') fail(param, "must not start with '/', got '" + frame + "'");
}

// The ROS parameter behind an error of make_stone, from the field its message starts with.
std::string stone_parameter(const std::string& message, const StoneSpec& spec) {
  auto starts_with = [&message](const char* field) { return message.rfind(field, 0) == 0; };
  if (starts_with("stone width")) return "stone/width";
  if (starts_with("unknown stone size")) return "stone/size";
  // Also "must be less than the width": the height comes from ~stone/height or ~stone/size.
  if (starts_with("stone height")) return spec.height ? "stone/height" : "stone/size";
  if (starts_with("unknown stone material")) return "stone/material";
  if (starts_with("density") && spec.density) return "stone/density";
  if (starts_with("mass") && spec.mass) return "stone/mass";
  // A derived mass, density or moment underflowed (a vanishing stone or override): blame the
  // override that set it, else the dimensions.
  if (spec.mass) return "stone/mass";
  if (spec.density) return "stone/density";
  return spec.height ? "stone/height" : "stone/width";
}

// make_stone checks every field of the spec; only its messages name core fields, not the
// ~stone/... parameters.
void check_stone(const StoneSpec& spec) {
  try {
    make_stone(spec);
  } catch (const InvalidArgument& e) {
    fail(stone_parameter(e.what(), spec), e.what());
  }
}

}  // namespace

std::int64_t dt_to_ns(double dt) {
  require_positive_param("dt", dt, "s");
  const double ns = dt * 1e9;
  if (ns > 1e15) fail("dt", "is too large: " + format_value(dt) + " s");
  const double whole = std::round(ns);
  if (std::abs(ns - whole) > 1e-6) {
    fail("dt", "must be a whole number of nanoseconds (stamps are whole nanoseconds), got " +
                   format_value(dt) + " s = " + format_value(ns) + " ns; try " +
                   format_value(whole * 1e-9) + " s");
  }
  const auto dt_ns = static_cast<std::int64_t>(whole);
  if (dt_ns < kMinDtNs) {
    fail("dt", "must be at least " + format_value(kMinDtNs * 1e-9) + " s, got " + format_value(dt) +
                   " s");
  }
  return dt_ns;
}

void validate_config(const StoneConfig& c) {
  if (!(c.rate >= kMinRate && c.rate <= kMaxRate)) {  // also refuses NaN
    fail("rate", "must be between " + format_value(kMinRate) + " and " + format_value(kMaxRate) +
                     " Hz, got " + format_value(c.rate));
  }
  const std::int64_t dt_ns = dt_to_ns(c.dt);
  try {
    motion_model_from_name(c.model);
  } catch (const InvalidArgument& e) {
    fail("model", e.what());
  }
  bool known_integrator = false;
  for (const std::string& name : integrator_names()) known_integrator |= name == c.integrator;
  if (!known_integrator) {
    std::string known;
    for (const std::string& name : integrator_names()) known += " " + name;
    fail("integrator", "unknown integrator '" + c.integrator + "' (known:" + known + ")");
  }
  require_finite_param("gravity", c.gravity);
  check_stone(c.stone);
  if (c.color != "black" && c.color != "white") {
    fail("stone/color", "must be 'black' or 'white', got '" + c.color + "'");
  }
  require_positive_param("max_angular_velocity", c.max_angular_velocity, "rad/s");
  if (!std::isfinite(c.auto_reset_period) || c.auto_reset_period < 0.0 ||
      c.auto_reset_period > 1e6) {
    fail("auto_reset_period",
         "must be between 0 (never) and 1e6 s, got " + format_value(c.auto_reset_period));
  }
  // A segment is reset at the first step at which its age reaches the period: one of ~dt or
  // less would reset the stone at every step, so it could never move.
  if (c.auto_reset_period > 0.0 && std::llround(c.auto_reset_period * 1e9) <= dt_ns) {
    fail("auto_reset_period", "must be 0 (never) or longer than ~dt " + format_value(c.dt) +
                                  " s, got " + format_value(c.auto_reset_period) + " s");
  }
  check_frame("world_frame", c.world_frame);
  check_frame("stone_frame", c.stone_frame);
  if (c.world_frame == c.stone_frame) {
    fail("stone_frame", "must differ from ~world_frame, both are '" + c.world_frame + "'");
  }
}

}  // namespace virtual_go
