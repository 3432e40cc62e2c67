// The world at the board's edges and on the table: a flat stone dropped just beyond the top edge
// hits the edge at the closed-form time and ends at rest on the table; one dropped just inside
// rests on the board overhanging the edge without ever touching it; stones sliding off the board
// (fast: flying off; slow: tipping over the edge in the fallback) land on the table and rest; a
// throw lands on the table beside the board. In every sampled state and every event: no overlap
// with the board or the table (a lower bound of the distance computed in the test), no energy
// gain, and the events of a 1 ms grid are those of one call to the end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/flight_reference.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;
using vg::WorldEventKind;

void expect_sound(const WorldRun& r, const std::string& what) {
  EXPECT_GE(r.worst_gap, -1e-12) << what;
  r.expect_no_energy_gain();
  EXPECT_LE(r.worst_quaternion_norm_error, 1e-12) << what;
  for (const auto& e : r.events) {
    if (e.kind == WorldEventKind::impact) EXPECT_LE(e.energy_change_j, 0.0) << what;
  }
  std::printf(
      "[ %-10s] %zu events, worst gap %.1e m, energy above start %.1e J, worst rise over "
      "an earlier state %.1e J\n",
      what.c_str(), r.events.size(), r.worst_gap, r.worst_energy_above_start, r.worst_energy_rise);
}

// The stone rests on the table, outside the board's footprint: its lowest point on z = -T.
void expect_resting_on_table(const vg::World& world, const std::string& what) {
  ASSERT_TRUE(world.is_resting(0)) << what;
  const vg::RigidBodyState& s = world.state(0);
  EXPECT_NEAR(plane_gap(s, -kThickness), 0.0, 1e-12) << what;
  const Vector3d p = lens_ref(s).support(-Vector3d::UnitZ());
  EXPECT_TRUE(std::abs(p.x()) > kHalfX || std::abs(p.y()) > kHalfY) << what;
  EXPECT_EQ(s.velocity_world, Vector3d::Zero()) << what;
  EXPECT_EQ(s.angular_momentum_world, Vector3d::Zero()) << what;
}

// Advances until every stone rests (or t_max), sampling on a 1 ms grid.
WorldRun run_to_rest(vg::World& world, double t_max) {
  WorldRun all;
  for (double t = 0.5; t <= t_max && !world.all_resting(); t += 0.5) run_into(all, world, t, 1e-3);
  return all;
}

TEST(WorldEdges, AFlatStoneDroppedJustBeyondTheEdgeHitsItThenRestsOnTheTable) {
  const double beyond = 0.002, h0 = 0.05;
  const vg::RigidBodyState start = at(Vector3d(kHalfX + beyond, 0.01, kC + h0));
  vg::World world(config(0.5), start, 0.0);
  const WorldRun r = run_to_rest(world, 60.0);
  // First contact: the bottom cap's sphere (centre d above G) reaches the edge line when its
  // centre is R from the line: z_S = sqrt(R^2 - beyond^2).
  const double z_hit = std::sqrt(kR * kR - beyond * beyond) - kD;
  const double t_hit = std::sqrt(2 * (kC + h0 - z_hit) / kG);
  const auto impacts = of_kind(r.events, WorldEventKind::impact);
  ASSERT_FALSE(impacts.empty());
  EXPECT_EQ(impacts[0].feature.kind, vg::BoardFeatureKind::top_edge);
  EXPECT_EQ(impacts[0].feature.index, 0);
  EXPECT_NEAR(impacts[0].time_s, t_hit, 1e-12);
  bool on_table = false;
  for (const auto& e : impacts)
    on_table = on_table || e.feature.kind == vg::BoardFeatureKind::table;
  EXPECT_TRUE(on_table);
  expect_resting_on_table(world, "edge out");
  expect_sound(r, "edge out");
  std::printf("[ edge out  ] edge hit at %.9f s (closed form %.9f), rest on the table at %.3f s\n",
              impacts[0].time_s, t_hit, last_of(r.events, WorldEventKind::rest)->time_s);
}

TEST(WorldEdges, AFlatStoneDroppedJustInsideTheEdgeRestsOverhangingWithoutTouchingIt) {
  const double inside = 0.002, h0 = 0.05;
  const vg::RigidBodyState start = at(Vector3d(kHalfX - inside, 0.01, kC + h0));
  vg::World world(config(0.5), start, 0.0);
  const WorldRun r = run(world, 0.5, 1e-3);
  ASSERT_TRUE(world.is_resting(0));
  for (const auto& e : r.events) {
    if (e.has_feature) EXPECT_EQ(e.feature.kind, vg::BoardFeatureKind::top_face);
  }
  // The gap to the edge line stays positive, and at rest it is the closed form: the cap's sphere
  // centre is R above the board, `inside` from the edge line.
  double closest = 1.0;
  for (const auto& s : r.states) {
    closest = std::min(
        closest, vgtest::line_gap_by_scan(lens_ref(s), Vector3d(kHalfX, 0, 0), Vector3d::UnitY()));
  }
  const double rest_gap = std::sqrt(inside * inside + kR * kR) - kR;
  EXPECT_GT(closest, 0.0);
  EXPECT_NEAR(
      vgtest::line_gap_by_scan(lens_ref(world.state(0)), Vector3d(kHalfX, 0, 0), Vector3d::UnitY()),
      rest_gap, 1e-12);
  EXPECT_NEAR(world.state(0).position_world.x(), kHalfX - inside, 1e-15);
  EXPECT_NEAR(plane_gap(world.state(0), 0.0), 0.0, 1e-15);
  EXPECT_EQ(world.counters().nonsmooth_steps, 0);
  expect_sound(r, "edge in");
  std::printf("[ edge in   ] closest approach to the edge %.6e m (at rest: %.6e m)\n", closest,
              rest_gap);
}

TEST(WorldEdges, AStoneSlidingOffTheBoardLandsOnTheTableAndRests) {
  // 0.5 m/s towards the +x edge, 3 cm away, mu 0.1: it reaches the edge fast enough to fly off.
  const vg::RigidBodyState start =
      at(Vector3d(kHalfX - 0.03, 0.02, kC), Quaterniond::Identity(), Vector3d(0.5, 0, 0));
  vg::World world(config(0.5, 0.1), start, 0.0);
  const WorldRun r = run_to_rest(world, 60.0);
  bool left = false, table = false;
  for (const auto& e : r.events) {
    left = left || e.detail == vg::WorldEventDetail::left_region;
    table = table ||
            (e.kind == WorldEventKind::impact && e.feature.kind == vg::BoardFeatureKind::table);
  }
  EXPECT_TRUE(left);
  EXPECT_TRUE(table);
  expect_resting_on_table(world, "slide off");
  expect_sound(r, "slide off");
}

TEST(WorldEdges, ASlowStoneTipsOverTheEdgeInTheFallbackAndComesToRest) {
  // mu 0.3: the stone reaches the edge at ~0.3 m/s, below sqrt(g R) = 0.39 m/s, so its cap
  // pivots on the edge (the nonsmooth fallback) before it falls.
  const vg::RigidBodyState start =
      at(Vector3d(kHalfX - 0.03, 0.0, kC), Quaterniond::Identity(), Vector3d(0.5, 0, 0));
  vg::World world(config(0.5, 0.3), start, 0.0);
  const WorldRun r = run_to_rest(world, 60.0);
  EXPECT_GT(world.counters().nonsmooth_steps, 10);
  ASSERT_TRUE(world.is_resting(0));
  // Wherever it settled (on the table, perhaps against the board's side): on the table plane.
  EXPECT_NEAR(plane_gap(world.state(0), -kThickness), 0.0, 1e-9);
  expect_sound(r, "tip over");
  std::printf("[ tip over  ] %ld fallback steps, %ld plastic impulses, rest (%s) at %.3f s\n",
              world.counters().nonsmooth_steps, world.counters().nonsmooth_impulses,
              vg::world_event_detail_name(last_of(r.events, WorldEventKind::rest)->detail).c_str(),
              last_of(r.events, WorldEventKind::rest)->time_s);
}

TEST(WorldEdges, AThrowLandsOnTheTableBesideTheBoard) {
  const double z0 = 0.05;
  const vg::RigidBodyState start =
      at(Vector3d(kHalfX + 0.05, -0.1, z0), Quaterniond::Identity(), Vector3d(0.2, 0, 0));
  vg::World world(config(0.5), start, 0.0);
  const WorldRun r = run_to_rest(world, 60.0);
  const auto impacts = of_kind(r.events, WorldEventKind::impact);
  ASSERT_FALSE(impacts.empty());
  EXPECT_EQ(impacts[0].feature.kind, vg::BoardFeatureKind::table);
  EXPECT_NEAR(impacts[0].time_s, std::sqrt(2 * (z0 + kThickness - kC) / kG), 1e-12);
  expect_resting_on_table(world, "table");
  expect_sound(r, "table");
}

TEST(WorldEdges, EventsDoNotDependOnTheSamplingGrid) {
  // The exact models never see the grid, and the fallback's sub-steps lie on a lattice from its
  // own start: a 1 ms grid and a single call give the same events.
  const vg::RigidBodyState start =
      at(Vector3d(kHalfX - 0.03, 0.0, kC), Quaterniond::Identity(), Vector3d(0.5, 0, 0));
  const double t_end = 0.6;
  vg::World gridded(config(0.5, 0.3), start, 0.0);
  const WorldRun r = run(gridded, t_end, 1e-3);
  vg::World once(config(0.5, 0.3), start, 0.0);
  std::vector<vg::WorldEvent> events;
  once.advance_to(t_end, events);
  ASSERT_EQ(events.size(), r.events.size());
  double worst_time = 0, worst_position = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].kind, r.events[i].kind);
    EXPECT_EQ(events[i].detail, r.events[i].detail);
    worst_time = std::max(worst_time, std::abs(events[i].time_s - r.events[i].time_s));
    worst_position = std::max(
        worst_position, (events[i].state.position_world - r.events[i].state.position_world).norm());
  }
  EXPECT_LE(worst_time, 1e-12);
  EXPECT_LE(worst_position, 1e-12);
  EXPECT_GT(gridded.counters().nonsmooth_steps, 10);
  std::printf(
      "[ grid      ] %zu events, 1 ms grid vs one call: times within %.1e s, positions "
      "within %.1e m\n",
      events.size(), worst_time, worst_position);
}

}  // namespace
