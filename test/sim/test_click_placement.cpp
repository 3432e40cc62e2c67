// ClickPlacement (rviz's Publish Point onto the board): a click sets a stone down at rest on the
// nearest Go point, colours alternating from black; a click off the board, onto a stone, or
// without a board places nothing, says why naming the point, and leaves the colour to come.
// Positions are checked against the board's own numbers written out here (lines 22 mm apart
// across, 23.7 mm along, tengen at the origin), not against the code's go_point_world.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sim/sim_test_support.h"
#include "virtual_go/sim/click_placement.h"
#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/stone_states.h"

namespace vg = virtual_go;
using namespace simtest;

namespace {

constexpr double kSpacingX = 0.022;   // m, the default board's lines across
constexpr double kSpacingY = 0.0237;  // m, along

void run(vg::StoneSimulation& sim, std::int64_t& now, std::int64_t duration_ns) {
  const std::int64_t end = now + duration_ns;
  for (; now <= end; now += 10 * kMs) {
    const vg::UpdateResult r = sim.update(now);
    ASSERT_TRUE(r.error.empty()) << r.error;
  }
}

// The world position of the intersection `column` (0 = A), `row` (0 = row 1), plus an offset in
// spacings.
Eigen::Vector3d near_point(int column, int row, double dx_spacings = 0.0,
                           double dy_spacings = 0.0) {
  return {(column - 9 + dx_spacings) * kSpacingX, (row - 9 + dy_spacings) * kSpacingY, 0.0};
}

const vg::StoneStateEntry* find(const std::vector<vg::StoneStateEntry>& entries,
                                const std::string& name) {
  for (const vg::StoneStateEntry& e : entries) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

}  // namespace

TEST(ClickPlacement, ClicksSetStonesDownAtTheNearestPointsAlternatingColours) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  run(sim, now, 10 * kMs);
  vg::ClickPlacement clicks;
  EXPECT_EQ(clicks.next_color(), vg::StoneColor::black);
  // Up to 0.45 spacing off an intersection in each direction, and above the board (a click on a
  // stone's top): the intersection below. D4 = column 3, row 3; Q16 = 15, 15; K4 = 8, 3.
  const struct {
    Eigen::Vector3d click;
    const char* point;
    const char* name;
    const char* color;
    int column, row;
  } expected[] = {
      {near_point(3, 3, 0.45, -0.45), "D4", "black_1", "black", 3, 3},
      {near_point(15, 15, -0.45, 0.45) + Eigen::Vector3d(0, 0, 0.0092), "Q16", "white_1", "white",
       15, 15},
      {near_point(8, 3, 0.3, 0.2), "J4", "black_2", "black", 8, 3},
  };
  for (const auto& e : expected) {
    const vg::ClickOutcome out = clicks.click(sim, e.click);
    EXPECT_TRUE(out.placed) << out.message;
    EXPECT_EQ(out.point, e.point);
    EXPECT_EQ(out.name, e.name);
  }
  EXPECT_EQ(clicks.next_color(), vg::StoneColor::white);
  run(sim, now, 30 * kMs);
  const std::vector<vg::StoneStateEntry> entries = vg::stone_states(sim);
  ASSERT_EQ(entries.size(), 4u);  // the initial stone and three clicked ones
  for (const auto& e : expected) {
    const vg::StoneStateEntry* s = find(entries, e.name);
    ASSERT_NE(s, nullptr) << e.name;
    EXPECT_EQ(s->point, e.point);
    EXPECT_EQ(s->color, e.color);
    // Set down through ~place's path: flat, at rest, exactly on the intersection, its lowest
    // point (half the lens's height below its centre) on the top face z = 0.
    EXPECT_TRUE(s->resting) << e.name;
    EXPECT_NEAR(s->output.position_world.x(), (e.column - 9) * kSpacingX, 1e-12);
    EXPECT_NEAR(s->output.position_world.y(), (e.row - 9) * kSpacingY, 1e-12);
    EXPECT_NEAR(s->output.position_world.z(), 0.5 * s->height_m, 1e-9);
    EXPECT_EQ(s->output.velocity_world.norm(), 0.0);
  }
}

TEST(ClickPlacement, AClickOffTheBoardPlacesNothingAndKeepsTheColour) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  run(sim, now, 10 * kMs);
  vg::ClickPlacement clicks;
  // Half a spacing beyond the outer lines (9.5 spacings from tengen) is the limit.
  const double eps = 1e-6;  // m
  const Eigen::Vector3d off[] = {
      {9.5 * kSpacingX + eps, 0.0, 0.0},
      {0.0, -9.5 * kSpacingY - eps, 0.0},
      {-9.5 * kSpacingX - eps, 9.5 * kSpacingY - eps, 0.0},
      {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0},
  };
  for (const Eigen::Vector3d& p : off) {
    const vg::ClickOutcome out = clicks.click(sim, p);
    EXPECT_FALSE(out.placed);
    EXPECT_EQ(out.point, "");
    EXPECT_NE(out.message.find("off the board"), std::string::npos) << out.message;
  }
  EXPECT_EQ(sim.pending_requests(), 0u);
  EXPECT_EQ(clicks.next_color(), vg::StoneColor::black);
  // Just inside: the outer lines' points T10 and K1, black then white.
  vg::ClickOutcome out = clicks.click(sim, {9.5 * kSpacingX - eps, 0.0, 0.0});
  EXPECT_TRUE(out.placed) << out.message;
  EXPECT_EQ(out.point, "T10");
  EXPECT_EQ(out.name, "black_1");
  out = clicks.click(sim, {0.0, -9.5 * kSpacingY + eps, 0.0});
  EXPECT_TRUE(out.placed) << out.message;
  EXPECT_EQ(out.point, "K1");
  EXPECT_EQ(out.name, "white_1");
}

TEST(ClickPlacement, AClickOntoAStonePlacesNothingAndNamesIt) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  run(sim, now, 3000 * kMs);  // the initial stone comes to rest on K10
  ASSERT_TRUE(sim.resting());
  vg::ClickPlacement clicks;
  vg::ClickOutcome out = clicks.click(sim, near_point(9, 9, 0.1, 0.1));
  EXPECT_FALSE(out.placed);
  EXPECT_EQ(out.point, "K10");
  EXPECT_NE(out.message.find("K10"), std::string::npos) << out.message;
  EXPECT_NE(out.message.find("stone already lies there"), std::string::npos) << out.message;

  ASSERT_TRUE(clicks.click(sim, near_point(2, 16)).placed);  // C17, black_1
  // Again before the next physics step (the placement still waits) and after it.
  out = clicks.click(sim, near_point(2, 16, -0.2, 0.3));
  EXPECT_FALSE(out.placed);
  EXPECT_NE(out.message.find("C17"), std::string::npos) << out.message;
  EXPECT_NE(out.message.find("black_1 already lies there"), std::string::npos) << out.message;
  run(sim, now, 20 * kMs);
  out = clicks.click(sim, near_point(2, 16, 0.4, 0.0));
  EXPECT_FALSE(out.placed);
  EXPECT_NE(out.message.find("black_1 already lies there"), std::string::npos) << out.message;
  EXPECT_EQ(sim.pending_requests(), 0u);
  EXPECT_EQ(clicks.next_color(), vg::StoneColor::white);  // refusals did not flip it
  ASSERT_EQ(vg::stone_states(sim).size(), 2u);

  // Taken off, the point is free again: the next colour, white.
  std::string answer;
  sim.remove("C17", answer);
  run(sim, now, 20 * kMs);
  out = clicks.click(sim, near_point(2, 16));
  EXPECT_TRUE(out.placed) << out.message;
  EXPECT_EQ(out.name, "white_1");
}

TEST(ClickPlacement, WithoutTheBoardAClickPlacesNothing) {
  vg::StoneSimulation sim{vg::StoneConfig{}};
  std::int64_t now = kStart;
  run(sim, now, 10 * kMs);
  vg::ClickPlacement clicks;
  const vg::ClickOutcome out = clicks.click(sim, near_point(3, 3));
  EXPECT_FALSE(out.placed);
  EXPECT_NE(out.message.find("no board"), std::string::npos) << out.message;
  EXPECT_EQ(clicks.next_color(), vg::StoneColor::black);
  EXPECT_EQ(sim.pending_requests(), 0u);
}
