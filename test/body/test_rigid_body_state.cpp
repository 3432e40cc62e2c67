// RigidBodyState: validation names the bad field; == is bitwise, so "left alone" can be
// checked also for states holding -0 or NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/common/validation.h"

namespace vg = virtual_go;

TEST(RigidBodyState, EqualityIsBitwise) {
  vg::RigidBodyState a;
  a.position_world = Eigen::Vector3d(1.0, 2.0, 3.0);
  a.angular_momentum_world = Eigen::Vector3d(1e-6, 0.0, -2e-6);
  vg::RigidBodyState b = a;
  EXPECT_TRUE(a == b);
  b.angular_momentum_world.y() = -0.0;  // numerically equal, another state's bits
  EXPECT_TRUE(b.angular_momentum_world.y() == a.angular_momentum_world.y());
  EXPECT_FALSE(a == b);
  EXPECT_TRUE(a != b);
  // A NaN left alone is the same state; a numeric comparison would call it different.
  a.velocity_world.x() = std::numeric_limits<double>::quiet_NaN();
  const vg::RigidBodyState copy = a;
  EXPECT_TRUE(copy == a);
  EXPECT_FALSE(copy.velocity_world.x() == a.velocity_world.x());
  // Every one of the 13 numbers counts.
  for (int i = 0; i < 4; ++i) {
    vg::RigidBodyState c = copy;
    c.orientation.coeffs()[i] = std::nextafter(c.orientation.coeffs()[i], 2.0);
    EXPECT_FALSE(c == copy) << i;
  }
  vg::RigidBodyState moved = copy;
  moved.position_world.z() = std::nextafter(3.0, 4.0);
  EXPECT_FALSE(moved == copy);
}

TEST(RigidBodyState, ValidationNamesTheField) {
  struct Case {
    const char* field;
    void (*spoil)(vg::RigidBodyState&);
  };
  const Case cases[] = {
      {"position", [](vg::RigidBodyState& s) { s.position_world.y() = INFINITY; }},
      {"velocity", [](vg::RigidBodyState& s) { s.velocity_world.z() = NAN; }},
      {"angular momentum", [](vg::RigidBodyState& s) { s.angular_momentum_world.x() = -INFINITY; }},
      {"orientation", [](vg::RigidBodyState& s) { s.orientation.coeffs().setZero(); }},
      {"orientation", [](vg::RigidBodyState& s) { s.orientation.w() = NAN; }},
  };
  for (const Case& c : cases) {
    vg::RigidBodyState s;
    c.spoil(s);
    try {
      s.validated();
      ADD_FAILURE() << c.field << " accepted";
    } catch (const vg::InvalidArgument& e) {
      EXPECT_EQ(e.field(), c.field) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(c.field, 0), 0u) << e.what();
    }
  }
}
