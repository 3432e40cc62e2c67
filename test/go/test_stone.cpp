// The stone catalogue: Japanese size numbers -> thickness, materials -> density, and how
// make_stone combines size, material and the explicit overrides (docs/physics.md, "Go stones").
#include <gtest/gtest.h>

#include <map>

#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;

TEST(Stone, SizeNumbersGiveTheTabulatedThickness) {
  // docs/physics.md, "Go stones", in mm.
  const std::map<int, double> table = {{22, 6.3},  {25, 7.0},  {28, 7.5},  {30, 8.0}, {31, 8.4},
                                       {32, 8.8},  {33, 9.2},  {34, 9.5},  {35, 9.8}, {36, 10.1},
                                       {37, 10.4}, {38, 10.7}, {39, 11.0}, {40, 11.3}};
  std::vector<int> expected_numbers;
  for (const auto& [number, mm] : table) {
    expected_numbers.push_back(number);
    EXPECT_NEAR(vg::thickness_for_size(number), mm * 1e-3, 1e-15) << number;
    const vg::LensShape shape = vg::lens_for_size(number);
    EXPECT_NEAR(shape.height(), mm * 1e-3, 1e-15) << number;
    EXPECT_EQ(shape.width(), 0.022) << number;
  }
  EXPECT_EQ(vg::size_numbers(), expected_numbers);
  // Thicker stones weigh more: mass grows monotonically with the size number.
  double previous = 0.0;
  for (int number : expected_numbers) {
    vg::StoneSpec spec;
    spec.size_number = number;
    const double m = vg::make_stone(spec).mass_properties.mass();
    EXPECT_GT(m, previous) << number;
    previous = m;
  }
}

TEST(Stone, MaterialsGiveTheirDensity) {
  const std::map<std::string, double> table = {
      {"slate", 2700.0}, {"shell", 2700.0}, {"glass", 2500.0}, {"yunzi", 2600.0}};
  std::vector<std::string> names;
  for (const auto& [name, rho] : table) {
    names.push_back(name);
    EXPECT_EQ(vg::material_density(name), rho) << name;
    vg::StoneSpec spec;
    spec.material = name;
    const vg::Stone stone = vg::make_stone(spec);
    EXPECT_EQ(stone.density, rho) << name;
    EXPECT_NEAR(stone.mass_properties.mass(), rho * stone.shape.volume(), 1e-18) << name;
  }
  EXPECT_EQ(vg::material_names(), names);
}

TEST(Stone, DefaultsAreSize33SlateTwentyTwoMillimetres) {
  const vg::Stone stone = vg::make_stone(vg::StoneSpec{});
  EXPECT_EQ(stone.shape.width(), 0.022);
  EXPECT_NEAR(stone.shape.height(), 9.2e-3, 1e-15);
  EXPECT_EQ(stone.density, 2700.0);
}

TEST(Stone, ExplicitValuesOverrideAndAreTakenAsGiven) {
  // Nothing is rounded or clamped: the values asked for are the values used.
  vg::StoneSpec spec;
  spec.size_number = 22;
  spec.width = 0.0222;      // a black stone
  spec.height = 0.0221999;  // overrides the size number; just below the width is allowed
  spec.material = "glass";
  spec.density = 1234.5;  // overrides the material
  vg::Stone stone = vg::make_stone(spec);
  EXPECT_EQ(stone.shape.width(), 0.0222);
  EXPECT_EQ(stone.shape.height(), 0.0221999);
  EXPECT_EQ(stone.density, 1234.5);
  EXPECT_NEAR(stone.mass_properties.mass(), 1234.5 * stone.shape.volume(), 1e-18);

  spec.mass = 7.25e-3;  // overrides density and material
  stone = vg::make_stone(spec);
  EXPECT_DOUBLE_EQ(stone.mass_properties.mass(), 7.25e-3);
  EXPECT_DOUBLE_EQ(stone.density, 7.25e-3 / stone.shape.volume());
}
