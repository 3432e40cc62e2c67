#include <gtest/gtest.h>

#include <cmath>

#include "virtual_go/contact/material.h"
#include "virtual_go/common/validation.h"

namespace vg = virtual_go;

TEST(ContactMaterial, RangesAreCheckedAndNamed) {
  EXPECT_NO_THROW(vg::validate_material("~contact/board", vg::ContactMaterial()));
  vg::ContactMaterial m;
  m.restitution = 1.0 + 1e-12;
  EXPECT_THROW(vg::validate_material("~contact/board", m), vg::InvalidArgument);
  m = vg::ContactMaterial();
  m.friction = NAN;
  try {
    vg::validate_material("~contact/table", m);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("~contact/table/friction"), std::string::npos);
  }
  m = vg::ContactMaterial();
  m.rolling_resistance_m = -1e-9;
  EXPECT_THROW(vg::validate_material("x", m), vg::InvalidArgument);
}
