// Parameter validation: every bad parameter is refused with its name in the message.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "virtual_go/sim/stone_config.h"
#include "virtual_go/sim/stone_parameters.h"

namespace vg = virtual_go;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Expects validate_config to refuse the config with a message starting "~param:".
void expect_refused(const std::string& param, const std::function<void(vg::StoneConfig&)>& edit) {
  vg::StoneConfig config;
  edit(config);
  try {
    vg::validate_config(config);
    ADD_FAILURE() << "~" << param << " was accepted";
  } catch (const vg::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("~" + param + ":", 0), 0u) << e.what();
    // The field, for callers, without reading the message; a parameter of the table.
    EXPECT_EQ(e.field(), "~" + param) << e.what();
    EXPECT_NE(vg::find_parameter(param), nullptr) << param;
  }
}

}  // namespace

TEST(StoneConfig, DefaultsAreValid) { EXPECT_NO_THROW(vg::validate_config(vg::StoneConfig())); }

// ~contact/stone/enabled reaches the world: stone contact is on by default (issue 15: stones
// touch, knock and rest against each other) and the parameter switches it off.
TEST(StoneConfig, StoneContactIsOnByDefaultAndTheParameterSetsIt) {
  vg::StoneConfig c;
  c.board_enabled = true;
  const vg::ParameterInfo* p = vg::find_parameter("contact/stone/enabled");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->default_text, "true");
  const vg::CheckedConfig on = vg::check_config(c);
  ASSERT_TRUE(on.world.has_value());
  EXPECT_TRUE(on.world->stone_contact);
  c.stone_contact = false;
  EXPECT_FALSE(vg::check_config(c).world->stone_contact);
}

TEST(StoneConfig, RateBoundsAreInclusive) {
  for (double rate : {vg::kMinRateHz, vg::kMaxRateHz}) {
    vg::StoneConfig config;
    config.rate_hz = rate;
    EXPECT_NO_THROW(vg::validate_config(config)) << rate;
  }
}

TEST(StoneConfig, AutoResetPeriodMustBeLongerThanAStep) {
  vg::StoneConfig config;
  config.auto_reset_period_s = 0.002;  // two steps: one step of motion, then the reset
  EXPECT_NO_THROW(vg::validate_config(config));
  config.auto_reset_period_s = 0.0;  // never
  EXPECT_NO_THROW(vg::validate_config(config));
  for (double period : {0.0009, 0.001}) {  // would reset at every step
    config.auto_reset_period_s = period;
    try {
      vg::validate_config(config);
      ADD_FAILURE() << "auto reset period " << period << " accepted with dt 0.001";
    } catch (const vg::ConfigError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("~auto_reset_period:", 0), 0u) << message;
      EXPECT_NE(message.find("longer than ~dt"), std::string::npos) << message;
    }
  }
}

TEST(StoneConfig, DtMustBeAWholeNumberOfNanoseconds) {
  EXPECT_EQ(vg::dt_to_ns(0.001), 1000000);
  EXPECT_EQ(vg::dt_to_ns(0.001666666), 1666666);  // 0.001666666 s
  EXPECT_EQ(vg::dt_to_ns(0.000001), 1000);
  try {
    vg::dt_to_ns(1.0 / 1024);  // 976562.5 ns
    ADD_FAILURE() << "half a nanosecond accepted";
  } catch (const vg::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("~dt"), std::string::npos) << message;
    EXPECT_NE(message.find("whole number of nanoseconds"), std::string::npos) << message;
  }
  for (double bad : {0.0, -0.001, kNaN, kInf, 1e-7}) {
    EXPECT_THROW(vg::dt_to_ns(bad), vg::ConfigError) << bad;
  }
}

TEST(StoneConfig, EachBadParameterIsNamed) {
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = 0.0; });
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = kNaN; });
  // The timer period 1 / rate: too long for ros::Duration, or rounding to 0 ns (busy loop).
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = 1e-12; });
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = 0.0009; });
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = 10001.0; });
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = 1e12; });
  expect_refused("rate", [](vg::StoneConfig& c) { c.rate_hz = kInf; });
  expect_refused("dt", [](vg::StoneConfig& c) { c.dt_s = 1.0 / 3000.0; });
  expect_refused("model", [](vg::StoneConfig& c) { c.model = "newtonian"; });
  expect_refused("integrator", [](vg::StoneConfig& c) { c.integrator = "verlet"; });
  expect_refused("gravity", [](vg::StoneConfig& c) { c.gravity_world.x() = kInf; });
  expect_refused("stone/size", [](vg::StoneConfig& c) { c.stone.size_number = 29; });
  expect_refused("stone/width", [](vg::StoneConfig& c) { c.stone.width = -0.022; });
  expect_refused("stone/height", [](vg::StoneConfig& c) { c.stone.height = 0.0; });
  expect_refused("stone/height", [](vg::StoneConfig& c) { c.stone.height = 0.03; });
  expect_refused("stone/material", [](vg::StoneConfig& c) { c.stone.material = "plastic"; });
  expect_refused("stone/density", [](vg::StoneConfig& c) { c.stone.density = kNaN; });
  expect_refused("stone/mass", [](vg::StoneConfig& c) { c.stone.mass = 0.0; });
  // make_stone names core fields; each must map to the parameter that was set.
  expect_refused("stone/size", [](vg::StoneConfig& c) {
    c.stone.size_number = 40;  // 11.3 mm, not less than the width
    c.stone.width = 0.011;
  });
  expect_refused("stone/height", [](vg::StoneConfig& c) {
    c.stone.size_number = 33;  // overridden by the height
    c.stone.height = 0.022;
  });
  expect_refused("stone/density", [](vg::StoneConfig& c) {
    c.stone.density = -1.0;  // checked even though the mass overrides it
    c.stone.mass = 0.005;
  });
  expect_refused("stone/mass", [](vg::StoneConfig& c) {
    c.stone.density = 2000.0;
    c.stone.mass = kInf;
  });
  expect_refused("stone/material", [](vg::StoneConfig& c) {
    c.stone.material = "x";  // a misspelt material is an error even when overridden
    c.stone.mass = 0.005;
  });
  expect_refused("stone/density", [](vg::StoneConfig& c) { c.stone.density = 1e-320; });
  expect_refused("stone/color", [](vg::StoneConfig& c) { c.color = "green"; });
  expect_refused("max_angular_velocity", [](vg::StoneConfig& c) { c.max_angular_velocity = -1; });
  expect_refused("auto_reset_period", [](vg::StoneConfig& c) { c.auto_reset_period_s = -0.5; });
  expect_refused("auto_reset_period", [](vg::StoneConfig& c) { c.auto_reset_period_s = kInf; });
  // Shorter than a step: the stone would be reset at every step.
  expect_refused("auto_reset_period", [](vg::StoneConfig& c) { c.auto_reset_period_s = 0.0005; });
  expect_refused("auto_reset_period", [](vg::StoneConfig& c) {
    c.dt_s = 0.01;
    c.auto_reset_period_s = 0.009;
  });
  expect_refused("world_frame", [](vg::StoneConfig& c) { c.world_frame = ""; });
  expect_refused("stone_frame", [](vg::StoneConfig& c) { c.stone_frame = "/stone"; });
  expect_refused("stone_frame", [](vg::StoneConfig& c) { c.stone_frame = "world"; });
}

namespace {

// The message of validate_config's refusal, or "accepted".
std::string refusal(const std::function<void(vg::StoneConfig&)>& edit) {
  vg::StoneConfig config;
  edit(config);
  try {
    vg::validate_config(config);
  } catch (const vg::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

// issue 8: ~initial/velocity and ~gravity with finite but absurd values were accepted; the node
// died 1.024 s later with a FATAL that named no parameter ("time 1.024 s is too large: the
// state overflows"). Now refused at start-up, naming the parameter, the value and the limit.
TEST(StoneConfig, AbsurdInitialVelocityAndGravityAreRefusedWithTheirLimits) {
  EXPECT_EQ(refusal([](vg::StoneConfig& c) {
              c.initial_velocity_world = Eigen::Vector3d(1.7564270946e+308, 0, 0);
            }),
            "~initial/velocity: |v| = 1.7564270946e+308 m/s exceeds ~max_speed 1000 m/s");
  EXPECT_EQ(
      refusal([](vg::StoneConfig& c) { c.gravity_world = Eigen::Vector3d(0, 0, -8.574e307); }),
      "~gravity: |g| = 8.574e+307 m/s^2 exceeds ~max_gravity 1000 m/s^2");
  EXPECT_EQ(
      refusal([](vg::StoneConfig& c) { c.initial_position_world = Eigen::Vector3d(0, 0, 1e300); }),
      "~initial/position: distance from the world origin = 1e+300 m exceeds "
      "~max_distance 1000 m");
  // The bounds are parameters: a scene that needs more sets them.
  EXPECT_EQ(refusal([](vg::StoneConfig& c) {
              c.gravity_world = Eigen::Vector3d(0, 0, -2000);
              c.max_gravity = 5000;
            }),
            "accepted");
}

// issue 8: a too-small ~stone/width (with the default size) was blamed on ~stone/size.
TEST(StoneConfig, TooSmallWidthIsBlamedOnTheWidth) {
  const std::string m = refusal([](vg::StoneConfig& c) { c.stone.width = 0.005; });
  EXPECT_EQ(m,
            "~stone/width: stone width 0.005 m must be more than the height 0.0092 m of the "
            "default size 33");
  // Below the plausible range: refused by the bound, also the width's.
  EXPECT_EQ(refusal([](vg::StoneConfig& c) { c.stone.width = 1e-200; }),
            "~stone/width: the width must be between ~min_width 0.001 and ~max_width 1 m, got "
            "1e-200 m");
}

// issue 8: a mass that made the principal moments subnormal was accepted, and the node then
// published omega_z 29.875 for a requested 30 (L = I w of a subnormal I keeps few digits).
TEST(StoneConfig, MassOutsideTheMassRangeIsRefused) {
  EXPECT_EQ(refusal([](vg::StoneConfig& c) { c.stone.mass = 1e-303; }),
            "~stone/mass: the mass must be between ~min_mass 1e-06 and ~max_mass 1000 kg, got "
            "1e-303 kg");
  EXPECT_EQ(refusal([](vg::StoneConfig& c) { c.stone.mass = 5000.0; }).rfind("~stone/mass:", 0),
            0u);
  // A mass from size and density is held to the same range, blamed on what set it.
  EXPECT_EQ(refusal([](vg::StoneConfig& c) {
              c.stone.density = 1e-3;
            }).rfind("~stone/density: the stone's mass (from its size and density)", 0),
            0u);
  EXPECT_EQ(refusal([](vg::StoneConfig& c) {
              c.stone.height = 1e-9;
            }).rfind("~stone/height: the stone's mass", 0),
            0u);
  EXPECT_EQ(refusal([](vg::StoneConfig& c) { c.stone.mass = 1e-6; }), "accepted");
}

// The bounds themselves: positive, within their caps (which keep every computed number finite,
// stone_config.h), min below max; each refusal names the bound.
TEST(StoneConfig, BoundsAreCheckedAgainstTheirCaps) {
  expect_refused("max_speed", [](vg::StoneConfig& c) { c.max_speed = 0.0; });
  expect_refused("max_speed", [](vg::StoneConfig& c) { c.max_speed = 3e8; });  // above light
  expect_refused("max_distance", [](vg::StoneConfig& c) { c.max_distance = 1e300; });
  expect_refused("max_gravity", [](vg::StoneConfig& c) { c.max_gravity = kNaN; });
  expect_refused("max_angular_velocity", [](vg::StoneConfig& c) { c.max_angular_velocity = 1e10; });
  expect_refused("min_mass", [](vg::StoneConfig& c) { c.min_mass = 1e-13; });
  expect_refused("max_mass", [](vg::StoneConfig& c) { c.max_mass = 1e13; });
  expect_refused("max_mass", [](vg::StoneConfig& c) {
    c.min_mass = 1.0;
    c.max_mass = 0.5;
  });
  expect_refused("min_width", [](vg::StoneConfig& c) { c.min_width = kInf; });
  expect_refused("max_width", [](vg::StoneConfig& c) { c.max_width = 1e4; });
  expect_refused("max_width", [](vg::StoneConfig& c) {
    c.min_width = 0.5;
    c.max_width = 0.5;
  });
  EXPECT_EQ(refusal([](vg::StoneConfig& c) { c.max_speed = 3e8; }),
            "~max_speed: must be positive and at most 299792458 m/s, got 300000000");
  // The caps themselves are accepted.
  EXPECT_EQ(refusal([](vg::StoneConfig& c) {
              c.max_speed = vg::kMaxSpeedCap;
              c.max_distance = vg::kMaxDistanceCap;
              c.max_gravity = vg::kMaxGravityCap;
              c.max_angular_velocity = vg::kMaxAngularVelocityCap;
              c.min_mass = vg::kMinMassCap;
              c.max_mass = vg::kMaxMassCap;
              c.min_width = vg::kMinWidthCap;
              c.max_width = vg::kMaxWidthCap;
            }),
            "accepted");
}
