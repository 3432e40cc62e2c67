// A real set's stones per colour (docs/physics.md, "Go stones"): black slate 22.2 mm, white
// shell 21.9 mm, size 33 (9.2 mm) unless set; masses against the lens volume's closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_go/common/validation.h"
#include "virtual_go/go/stone_set.h"

namespace vg = virtual_go;

namespace {

// Mass of a uniform lens of width w, height h (m) and density rho: V = pi c (3 a^2 + c^2) / 3.
double lens_mass(double w, double h, double rho) {
  const double a = w / 2, c = h / 2;
  return rho * M_PI * c * (3 * a * a + c * c) / 3;
}

}  // namespace

TEST(StoneSet, DefaultsAreARealSet) {
  const vg::StoneSet set;
  const vg::StoneBody black = vg::make_stone_body(set, vg::StoneColor::black);
  const vg::StoneBody white = vg::make_stone_body(set, vg::StoneColor::white);
  EXPECT_EQ(black.color, vg::StoneColor::black);
  EXPECT_EQ(white.color, vg::StoneColor::white);
  EXPECT_EQ(black.stone.shape.width(), 0.0222);
  EXPECT_EQ(white.stone.shape.width(), 0.0219);
  EXPECT_EQ(black.stone.shape.height(), 0.0092);  // size 33
  EXPECT_EQ(white.stone.shape.height(), 0.0092);
  EXPECT_EQ(set.black.material, "slate");
  EXPECT_EQ(set.white.material, "shell");
  // Slate and shell are both 2700 kg/m^3: the masses differ by the width only.
  EXPECT_NEAR(black.stone.mass_properties.mass(), lens_mass(0.0222, 0.0092, 2700.0), 1e-15);
  EXPECT_NEAR(white.stone.mass_properties.mass(), lens_mass(0.0219, 0.0092, 2700.0), 1e-15);
  EXPECT_GT(black.stone.mass_properties.mass(), white.stone.mass_properties.mass());
  // The contact geometry is the shape's: a = w/2, c = h/2, R = (a^2 + c^2) / 2c.
  const double a = 0.0111, c = 0.0046;
  EXPECT_NEAR(black.lens.half_width(), a, 1e-18);
  EXPECT_NEAR(black.lens.half_height(), c, 1e-18);
  EXPECT_NEAR(black.lens.sphere_radius(), (a * a + c * c) / (2 * c), 1e-17);
  EXPECT_NEAR(white.lens.half_width(), 0.01095, 1e-18);
}

TEST(StoneSet, EachColourCanBeChanged) {
  vg::StoneSet set;
  set.spec(vg::StoneColor::white).size_number = 36;  // 10.1 mm
  set.black.material = "glass";
  const vg::StoneBody black = vg::make_stone_body(set, vg::StoneColor::black);
  const vg::StoneBody white = vg::make_stone_body(set, vg::StoneColor::white);
  EXPECT_EQ(white.stone.shape.height(), 0.0101);
  EXPECT_EQ(black.stone.shape.height(), 0.0092);
  EXPECT_NEAR(black.stone.mass_properties.mass(), lens_mass(0.0222, 0.0092, 2500.0), 1e-15);
  EXPECT_NEAR(white.stone.mass_properties.mass(), lens_mass(0.0219, 0.0101, 2700.0), 1e-15);
}

TEST(StoneSet, BadSpecNamesTheColourAndField) {
  vg::StoneSet set;
  set.white.width = 0.005;  // below the size-33 thickness
  try {
    vg::make_stone_body(set, vg::StoneColor::white);
    FAIL() << "accepted a white stone narrower than it is thick";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "white/width");
    EXPECT_NE(std::string(e.what()).find("0.005"), std::string::npos) << e.what();
  }
  set.black.material = "wood";
  try {
    vg::make_stone_body(set, vg::StoneColor::black);
    FAIL() << "accepted an unknown material";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "black/material");
  }
  // The other colour is unaffected.
  EXPECT_NO_THROW(
      vg::make_stone_body(vg::StoneColor::black, vg::set_stone_spec(vg::StoneColor::black)));
}
