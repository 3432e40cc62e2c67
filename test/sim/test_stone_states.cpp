// ~stones' content without ROS (sim/stone_states): every field of the single stone against
// facts the test computes itself (the lens volume, the board's line spacing, free fall), and
// when the message goes out.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_go/sim/stone_states.h"

namespace vg = virtual_go;

namespace {

constexpr std::int64_t kStart = 1700000000123456789;
constexpr std::int64_t kMs = 1000000;
constexpr double kG = 9.80665;

// A white stone 22 mm x 9 mm of slate held flat 2 cm above the point at (x, y), released at rest.
vg::StoneConfig drop_at(double x_m, double y_m) {
  vg::StoneConfig c;
  c.board_enabled = true;
  c.auto_reset_period_s = 0.0;
  c.color = "white";
  c.stone_frame = "white_1";
  c.stone.width = 0.022;
  c.stone.height = 0.009;
  c.stone.density = 2700.0;
  c.initial_position_world = Eigen::Vector3d(x_m, y_m, 0.0045 + 0.02);
  return c;
}

vg::StoneStateEntry only_entry(const vg::StoneSimulation& sim) {
  const std::vector<vg::StoneStateEntry> states = vg::stone_states(sim);
  EXPECT_EQ(states.size(), 1u);
  return states.at(0);
}

}  // namespace

TEST(StoneStates, SingleStoneFieldsFromItsSpecTheBoardAndFreeFall) {
  // D4: column D (index 3), row 4 (index 3), 6 lines from tengen either way; lines 22 mm apart
  // across and 23.7 mm along (the default board), nudged 5 mm off the point.
  vg::StoneSimulation sim(drop_at(-6 * 0.022 + 0.005, -6 * 0.0237 - 0.005));
  ASSERT_TRUE(sim.update(kStart).advanced);
  vg::StoneStateEntry e = only_entry(sim);
  EXPECT_EQ(e.name, "white_1");
  EXPECT_EQ(e.color, "white");
  EXPECT_EQ(e.point, "D4");
  EXPECT_DOUBLE_EQ(e.width_m, 0.022);
  EXPECT_DOUBLE_EQ(e.height_m, 0.009);
  // V = pi c (3a^2 + c^2) / 3 with a = w/2, c = h/2 (docs/DESIGN: 4.876 g for slate).
  const double a = 0.011, c = 0.0045;
  EXPECT_NEAR(e.mass_kg, 2700.0 * M_PI * c * (3 * a * a + c * c) / 3.0, 1e-15);
  EXPECT_NEAR(e.mass_kg, 4.876e-3, 1e-6);
  EXPECT_FALSE(e.resting);

  // 50 ms of free fall (the 2 cm drop takes 64 ms): v = -g t, z = z0 - g t^2 / 2, no spin.
  ASSERT_TRUE(sim.update(kStart + 50 * kMs).advanced);
  e = only_entry(sim);
  EXPECT_NEAR(e.output.velocity_world.z(), -kG * 0.05, 1e-12);
  EXPECT_NEAR(e.output.position_world.z(), 0.0245 - 0.5 * kG * 0.05 * 0.05, 1e-12);
  EXPECT_EQ(e.output.position_world.x(), -6 * 0.022 + 0.005);
  EXPECT_EQ(e.output.angular_velocity_world, Eigen::Vector3d::Zero());
  EXPECT_EQ(e.point, "D4");

  // Dropped flat on the board it comes to rest: all velocities exactly zero.
  std::int64_t now = kStart + 50 * kMs;
  for (int i = 0; i < 200 && !sim.resting(); ++i) sim.update(now += 16 * kMs);
  ASSERT_TRUE(sim.resting());
  e = only_entry(sim);
  EXPECT_TRUE(e.resting);
  EXPECT_EQ(e.output.velocity_world, Eigen::Vector3d::Zero());
  EXPECT_EQ(e.output.angular_velocity_world, Eigen::Vector3d::Zero());
  EXPECT_NEAR(e.output.position_world.z(), 0.0045, 1e-7);  // lying on the board's top, z = 0
}

// Off the grid: more than half a spacing outside the outer lines (9.5 spacings from tengen).
TEST(StoneStates, NoPointOffTheGridOrOnAnotherBoardOrWithoutOne) {
  vg::StoneSimulation off(drop_at(9.6 * 0.022, 0.0));
  ASSERT_TRUE(off.update(kStart).advanced);
  EXPECT_EQ(only_entry(off).point, "");

  vg::StoneSimulation edge(drop_at(9.4 * 0.022, 9.4 * 0.0237));
  ASSERT_TRUE(edge.update(kStart).advanced);
  EXPECT_EQ(only_entry(edge).point, "T19");

  // No parameter makes another board (tests may alter a checked configuration).
  vg::CheckedConfig thirteen = vg::check_config(drop_at(0.0, 0.0));
  thirteen.world->board.lines = 13;
  vg::StoneSimulation small(thirteen);
  ASSERT_TRUE(small.update(kStart).advanced);
  EXPECT_EQ(only_entry(small).point, "");

  vg::StoneConfig no_board = drop_at(0.0, 0.0);
  no_board.board_enabled = false;
  vg::StoneSimulation flying(no_board);
  ASSERT_TRUE(flying.update(kStart).advanced);
  EXPECT_EQ(only_entry(flying).point, "");
  EXPECT_EQ(only_entry(flying).color, "white");
}

TEST(StoneStates, DueOnEveryChangeAndWhileMovingOnlyWhenListened) {
  vg::UpdateResult r;
  EXPECT_FALSE(vg::stone_states_due(r, false, true)) << "no new state";
  r.advanced = true;
  EXPECT_TRUE(vg::stone_states_due(r, false, true));
  EXPECT_FALSE(vg::stone_states_due(r, false, false)) << "moving, nobody listens";
  EXPECT_FALSE(vg::stone_states_due(r, true, true)) << "all resting, nothing changed";
  r.events.emplace_back();
  EXPECT_TRUE(vg::stone_states_due(r, true, false)) << "a change goes out latched";
  EXPECT_TRUE(vg::stone_states_due(r, false, false));
}
