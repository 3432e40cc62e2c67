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
