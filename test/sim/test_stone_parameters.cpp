// The node's parameter table: every StoneConfig field once, defaults taken from StoneConfig, and
// README.md's parameter table restating it row for row.
#include <gtest/gtest.h>

#include <set>

#include "support/readme_tables.h"
#include "virtual_go/sim/stone_parameters.h"

namespace vg = virtual_go;

TEST(StoneParameters, EachFieldOnceUnderAUniqueName) {
  vg::StoneConfig config;
  std::set<std::string> names;
  std::set<const void*> fields;
  for (const vg::BoundParameter& p : vg::bind_parameters(config)) {
    EXPECT_TRUE(names.insert(p.info.name).second) << "twice: " << p.info.name;
    const void* field = std::visit([](auto* f) -> const void* { return f; }, p.field);
    EXPECT_TRUE(fields.insert(field).second) << p.info.name << " shares a field";
    // The field lies inside this config (not in a copy or elsewhere).
    EXPECT_GE(static_cast<const char*>(field), reinterpret_cast<const char*>(&config));
    EXPECT_LT(static_cast<const char*>(field), reinterpret_cast<const char*>(&config + 1));
    EXPECT_EQ(p.info.help.find('|'), std::string::npos) << p.info.name;
    EXPECT_NE(vg::find_parameter(p.info.name), nullptr);
  }
  EXPECT_EQ(vg::find_parameter("rat"), nullptr);
}

TEST(StoneParameters, DefaultsAreTheConfigsOwn) {
  // Set every bound field to a recognisable value through the table, then read it back
  // directly: the table writes the field it says.
  vg::StoneConfig config;
  for (const vg::BoundParameter& p : vg::bind_parameters(config)) {
    if (p.info.name == "rate") *std::get<double*>(p.field) = 25.0;
    if (p.info.name == "stone/size") *std::get<std::optional<int>*>(p.field) = 40;
    if (p.info.name == "initial/orientation") {
      *std::get<Eigen::Vector4d*>(p.field) = Eigen::Vector4d(0, 0, 1, 0);
    }
  }
  EXPECT_EQ(config.rate_hz, 25.0);
  EXPECT_EQ(config.stone.size_number, 40);
  EXPECT_EQ(config.initial_orientation_xyzw, Eigen::Vector4d(0, 0, 1, 0));
  // Defaults as the table shows them.
  EXPECT_EQ(vg::find_parameter("rate")->default_text, "60");
  EXPECT_EQ(vg::find_parameter("dt")->default_text, "0.001");
  EXPECT_EQ(vg::find_parameter("gravity")->default_text, "[0, 0, -9.80665]");
  EXPECT_EQ(vg::find_parameter("stone/size")->default_text, "33 = 9.2 mm");
  EXPECT_EQ(vg::find_parameter("stone/height")->default_text, "");
}

// README.md restates the table for readers: same names in the same order, units, defaults and
// help.
TEST(StoneParameters, ReadmeTableMatchesTheTable) {
  const auto rows = vgtest::readme_table(VG_README, "### Parameters");
  const auto& parameters = vg::stone_parameters();
  ASSERT_EQ(rows.size(), parameters.size()) << "README.md, \"### Parameters\"";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const vg::ParameterInfo& p = parameters[i];
    ASSERT_EQ(rows[i].size(), 4u) << p.name;
    EXPECT_EQ(rows[i][0], "~" + p.name);
    EXPECT_EQ(rows[i][1], p.unit) << p.name;
    EXPECT_EQ(rows[i][2], p.default_text) << p.name;
    EXPECT_EQ(rows[i][3], p.help) << p.name;
  }
}
