// Stone-stone contact in the World (docs/physics.md, "World", "Stone-stone contact in the world"),
// checked against physics written here: the closed-form time and outcome of a central impact of
// two equal stones (momentum, Newton/Stronge restitution for a central frictionless impact), an
// independent lens-lens gap bound (support planes, convex_reference.h), the energy from the
// inertia tensor, exact rest, and determinism.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "world/many_stones_support.h"
#include "world/static_balance.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;
using vg::StoneId;
using vg::WorldEventKind;

// A lower bound of the signed distance between two stones of the default body
// (many_stones_support.h: supporting planes, the test's own support mapping).
double pair_gap_bound(const vg::RigidBodyState& sa, const vg::RigidBodyState& sb) {
  return worldtest::pair_gap_bound(lens_ref(sa), lens_ref(sb));
}

double total_energy(const vg::World& w) {
  double e = 0.0;
  for (std::size_t i = 0; i < w.stone_count(); ++i) e += energy(w.state(i));
  return e;
}

// The default world with stone-stone contact on (WorldConfig::stone_contact, off by default).
vg::WorldConfig contact_config(double restitution = 0.5) {
  vg::WorldConfig c = config(restitution);
  c.stone_contact = true;
  return c;
}

// Two equal stones in flight, centres at the same height on the x axis, approaching at 1 m/s
// each: A flat, B standing on its rim with its axis along x, so A's rim meets B's cap apex on
// the line of centres (a central impact, no rotation, friction does nothing).
struct HeadOn {
  double d = 0.05;  // half the initial distance of the centres, m
  vg::World world;
  explicit HeadOn(double restitution)
      : world([&] {
          vg::WorldConfig c = contact_config();
          c.board_enabled = false;
          c.stone_material.restitution = restitution;
          c.stone_material.friction = 0.0;
          const Quaterniond on_rim(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()));
          return vg::World(
              c,
              std::vector<vg::RigidBodyState>{
                  at(Vector3d(-0.05, 0, 0.3), Quaterniond::Identity(), Vector3d(1, 0, 0)),
                  at(Vector3d(0.05, 0, 0.3), on_rim, Vector3d(-1, 0, 0))},
              0.0);
        }()) {}
};

TEST(WorldContacts, HeadOnImpactOfTwoFlightsIsExact) {
  for (const double e : {1.0, 0.5}) {
    SCOPED_TRACE(e);
    HeadOn h(e);
    std::vector<vg::WorldEvent> events;
    for (int k = 1; k <= 60; ++k) h.world.advance_to(k * 1e-3, events);
    const std::vector<vg::WorldEvent> impacts = of_kind(events, WorldEventKind::impact);
    ASSERT_EQ(impacts.size(), 2u);
    // The gap 2d - a - c closes at 2 m/s (gravity acts on both alike).
    const double t_hit = (2 * h.d - kA - kC) / 2.0;
    const vg::WorldEvent& ea = impacts[0].id == h.world.id(0) ? impacts[0] : impacts[1];
    const vg::WorldEvent& eb = impacts[0].id == h.world.id(0) ? impacts[1] : impacts[0];
    EXPECT_NEAR(ea.time_s, t_hit, 1e-12);
    EXPECT_EQ(ea.time_s, eb.time_s);
    ASSERT_TRUE(ea.other && eb.other);
    EXPECT_EQ(*ea.other, h.world.id(1));
    EXPECT_EQ(*eb.other, h.world.id(0));
    // Momentum: 0 along x before; the same after, to round-off.
    const Vector3d p_after = mass() * (ea.state.velocity_world + eb.state.velocity_world);
    EXPECT_NEAR(p_after.x(), 0.0, 1e-15);
    // Both fell for t_hit: v_z = -g t before and after (the impulse is along x).
    EXPECT_NEAR(ea.state.velocity_world.z(), -kG * t_hit, 1e-12);
    EXPECT_NEAR(eb.state.velocity_world.z(), -kG * t_hit, 1e-12);
    // Equal masses, central: v_A = -e, v_B = +e (e = 1: the velocities are exchanged).
    EXPECT_NEAR(ea.state.velocity_world.x(), -e, 1e-12);
    EXPECT_NEAR(eb.state.velocity_world.x(), e, 1e-12);
    EXPECT_NEAR(omega_of(ea.state).norm(), 0.0, 1e-9);
    // Energy: -(1 - e^2) (1/2) (m/2) u^2 with u = 2 m/s.
    const double de = -(1 - e * e) * mass();
    EXPECT_NEAR(ea.energy_change_j, de, 1e-12 * mass());
    const double before =
        2 * (0.5 * mass() * (1 + std::pow(kG * t_hit, 2))) - 2 * mass() * kGravity.z() * 0.0;
    const double after =
        0.5 * mass() *
        (ea.state.velocity_world.squaredNorm() + eb.state.velocity_world.squaredNorm());
    EXPECT_NEAR(after - before, de, 1e-12);
    EXPECT_NEAR(ea.approach_speed_mps, 2.0, 1e-9);
    EXPECT_NEAR(ea.rebound_speed_mps, 2.0 * e, 1e-9);
    // After: apart, flying apart in closed form.
    EXPECT_EQ(h.world.mode(std::size_t{0}), vg::StoneMode::flight);
    EXPECT_GT(pair_gap_bound(h.world.state(std::size_t{0}), h.world.state(std::size_t{1})), 0.0);
    EXPECT_EQ(h.world.counters().pair_impacts, 1);
  }
}

// A stone set down resting at the centre, another dropped onto it from 5 cm.
struct Dropped {
  vg::World world;
  StoneId lower, upper;
  Dropped() : world(contact_config(0.5), std::vector<vg::RigidBodyState>{}, 0.0) {
    std::vector<vg::WorldEvent> events;
    lower = world.add_stone(0, at(Vector3d(0, 0, kC)), 0.0, events);
    upper = world.add_stone(0, at(Vector3d(0.002, 0.001, 0.05)), 0.0, events);
  }
};

struct DropRecord {
  std::vector<vg::WorldEvent> events;
  std::vector<vg::RigidBodyState> final_states;
  double worst_pair_gap = std::numeric_limits<double>::infinity();
  double worst_board_gap = std::numeric_limits<double>::infinity();
  double worst_energy_rise = 0.0;
};

DropRecord run_drop(Dropped& d, double t_end) {
  DropRecord r;
  double lowest = total_energy(d.world);
  const double scale = std::abs(lowest) + 2 * mass() * kG * kA;
  const auto check = [&] {
    const vg::RigidBodyState& a = d.world.state(d.lower);
    const vg::RigidBodyState& b = d.world.state(d.upper);
    r.worst_pair_gap = std::min(r.worst_pair_gap, pair_gap_bound(a, b));
    r.worst_board_gap = std::min({r.worst_board_gap, proven_gap(a), proven_gap(b)});
    const double e = total_energy(d.world);
    r.worst_energy_rise = std::max(r.worst_energy_rise, (e - lowest) / scale);
    lowest = std::min(lowest, e);
  };
  check();
  for (long k = 1; k * 1e-3 <= t_end + 1e-12; ++k) {
    d.world.advance_to(k * 1e-3, r.events);
    check();
  }
  for (std::size_t i = 0; i < d.world.stone_count(); ++i)
    r.final_states.push_back(d.world.state(i));
  return r;
}

TEST(WorldContacts, AStoneDroppedOnARestingStoneWakesItAndNeverPassesThrough) {
  Dropped d;
  const DropRecord r = run_drop(d, 10.0);
  const vg::WorldCounters& n = d.world.counters();
  std::printf(
      "drop on a resting stone, 10 s: %ld pipeline passes, %ld gap checks, %ld pair "
      "searches, %ld islands, %ld events, work %ld\n",
      n.stages, n.pair_gap_checks, n.pair_searches, n.islands_formed, n.events, n.work());
  // The first impact names both and wakes the lower stone.
  const vg::WorldEvent* first = nullptr;
  for (const vg::WorldEvent& e : r.events) {
    if (e.kind == WorldEventKind::impact && e.other) {
      first = &e;
      break;
    }
  }
  ASSERT_NE(first, nullptr);
  // Its bottom falls 5 cm - 3c onto the lower stone's top (both flat, nearly centred).
  EXPECT_NEAR(first->time_s, std::sqrt(2 * (0.05 - 3 * kC) / kG), 1e-4);
  bool woke = false, impact_named = false;
  for (const vg::WorldEvent& e : r.events) {
    if (e.kind == WorldEventKind::wake && e.id == d.lower && e.other == d.upper) woke = true;
    if (e.kind == WorldEventKind::impact && e.id == d.lower && e.other == d.upper)
      impact_named = true;
  }
  EXPECT_TRUE(woke);
  EXPECT_TRUE(impact_named);
  EXPECT_GE(r.worst_pair_gap, -1e-9);
  EXPECT_GE(r.worst_board_gap, -1e-9);
  EXPECT_LE(r.worst_energy_rise, 1e-11);
  ASSERT_TRUE(d.world.all_resting());
  // Both at rest are held by their contacts (static_balance.h: forces and couples inside the
  // contact laws; measured 9e-17 of m g).
  EXPECT_EQ(print_unheld("drop on a resting stone", d.world, kGravity), 0);
  // Resting: bitwise still, and costing nothing.
  const vg::WorldCounters before = d.world.counters();
  std::vector<vg::WorldEvent> later;
  for (int k = 1; k <= 1000; ++k) d.world.advance_to(10.0 + k * 1e-3, later);
  EXPECT_TRUE(later.empty());
  EXPECT_EQ(d.world.counters().work(), before.work());
  EXPECT_EQ(d.world.counters().stones_visited, before.stones_visited);
  for (std::size_t i = 0; i < d.world.stone_count(); ++i) {
    EXPECT_TRUE(d.world.state(i) == r.final_states[i]);
    EXPECT_EQ(d.world.state(i).velocity_world, Vector3d::Zero());
  }
  // The upper stone ended on the lower one or on the board, above the board in both cases.
  EXPECT_GT(d.world.state(d.upper).position_world.z(), kC - 1e-9);
}

// The work budget covers the pair search and the islands: the drop above (its costly part,
// two stones in plane contact side by side, is in its first 0.5 s) with about a grid interval's
// sub-steps per call (1 ms / h units). Every call makes progress and stays within the bound
// (world.h: 2 max_steps, plus one pass's pair work and one unit per stone or island in contact; a
// handful here), and the states are the same as without a budget at the times both reach (the
// budget only cuts the work into calls).
TEST(WorldContacts, AWorkBudgetBoundsThePairSearchAndTheIslands) {
  Dropped budgeted, free_run;
  // About one grid interval's island sub-steps (1 ms / h): with the pair search's work on top,
  // the drop's calls exceed it.
  const long grid_steps = std::lround(1e-3 / vg::NonsmoothContactOptions{}.step_s);
  const vg::WorkBudget budget{std::max(1L, grid_steps)};
  std::vector<vg::WorldEvent> events;
  long calls = 0, largest = 0;
  for (int k = 1; k <= 500; ++k) {
    const double t = k * 1e-3;
    for (;;) {
      const double before = budgeted.world.time();
      const vg::AdvanceResult r = budgeted.world.advance_to(t, events, budget);
      ++calls;
      largest = std::max(largest, r.work);
      ASSERT_LE(r.work, 2 * budget.max_steps + 16) << "at " << before << " s";
      if (r.reached) break;
      ASSERT_GT(budgeted.world.time(), before) << "no progress at " << before << " s";
    }
    free_run.world.advance_to(t, events);
    if (k % 100 == 0) {
      for (std::size_t i = 0; i < 2; ++i)
        EXPECT_TRUE(budgeted.world.state(i) == free_run.world.state(i))
            << "stone " << i << " at " << t;
    }
  }
  std::printf("budget 10: %ld calls for 500 grid times, largest call %ld units\n", calls, largest);
  EXPECT_GT(calls, 500);  // the budget did cut some calls
}

TEST(WorldContacts, TheSameDropTwiceIsBitwiseTheSame) {
  Dropped d1, d2;
  const DropRecord r1 = run_drop(d1, 1.0);
  const DropRecord r2 = run_drop(d2, 1.0);
  ASSERT_EQ(r1.events.size(), r2.events.size());
  for (std::size_t k = 0; k < r1.events.size(); ++k) {
    EXPECT_EQ(r1.events[k].time_s, r2.events[k].time_s);
    EXPECT_EQ(r1.events[k].kind, r2.events[k].kind);
    EXPECT_TRUE(r1.events[k].state == r2.events[k].state);
  }
  for (std::size_t i = 0; i < r1.final_states.size(); ++i)
    EXPECT_TRUE(r1.final_states[i] == r2.final_states[i]);
}

// A resting row is not touched by a stone that lands and rests elsewhere: only what is hit
// wakes; the row's stones are never visited.
TEST(WorldContacts, ARestingRowIsUnaffectedByAStoneRestingElsewhere) {
  vg::World world(contact_config(0.5), std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> events;
  std::vector<StoneId> row;
  for (int k = 0; k < 5; ++k)
    row.push_back(world.add_stone(0, at(Vector3d(-0.05 + 0.023 * k, 0, kC)), 0.0, events));
  world.advance_to(0.0, events);
  ASSERT_TRUE(world.all_resting());
  std::vector<vg::RigidBodyState> frozen;
  for (const StoneId id : row) frozen.push_back(world.state(id));
  const std::size_t before = events.size();
  const StoneId dropped = world.add_stone(0, at(Vector3d(0.1, 0.12, 0.03)), 0.0, events);
  for (int k = 1; k <= 2000; ++k) world.advance_to(k * 1e-3, events);
  EXPECT_TRUE(world.all_resting());
  EXPECT_TRUE(world.is_resting(dropped));
  for (std::size_t k = 0; k < row.size(); ++k) EXPECT_TRUE(world.state(row[k]) == frozen[k]);
  for (std::size_t k = before; k < events.size(); ++k) EXPECT_EQ(events[k].id, dropped);
  EXPECT_EQ(world.counters().pair_impacts, 0);
  EXPECT_EQ(world.counters().islands_formed, 0);
}

// The stone material is validated like the others.
TEST(WorldContacts, ABadStoneMaterialIsRefusedNamingIt) {
  vg::WorldConfig c = contact_config();
  c.stone_material.friction = -1.0;
  try {
    vg::World w(c, at(Vector3d(0, 0, 0.1)), 0.0);
    FAIL() << "accepted a negative stone friction";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field().rfind("contact/stone", 0), 0u) << e.field();
  }
}

}  // namespace
