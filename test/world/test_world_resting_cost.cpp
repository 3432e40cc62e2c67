// A resting full board costs nothing per advance_to, also while another stone moves (issue 15:
// O(1) in resting stones), with stone contact on. Counted, not timed: the same stone thrown over
// the table beside the board does exactly the same work (visits, broad-phase tests, pair tests,
// passes, integration work) and follows bit for bit the same path with 361 stones resting on the
// board as with one resting stone, and the resting stones' poses stay frozen bit for bit.
#include <gtest/gtest.h>

#include <vector>

#include "virtual_go/go/go_point.h"
#include "virtual_go/world/stone_placement.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;

vg::WorldConfig contact_config() {
  vg::WorldConfig c = config(0.5);
  c.stone_contact = true;
  return c;
}

// Every point of the grid set down (or only A1), checkered, all resting.
vg::World board_of(bool full) {
  vg::World world(contact_config(), std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> events;
  const int points = full ? vg::kGoLines * vg::kGoLines : 1;
  for (int index = 0; index < points; ++index) {
    const vg::GoPoint p = vg::point_at_index(index);
    const vg::StoneColor colour =
        (p.column + p.row) % 2 == 0 ? vg::StoneColor::black : vg::StoneColor::white;
    (void)vg::set_down_stone(world, colour, p, 0.0, events);
  }
  world.advance_to(1e-3, events);
  return world;
}

// The stone thrown over the table, 14 cm beyond the board's +x side and 10 cm above the table,
// moving away from the board and spinning: it falls, bounces, slides and settles there. Its
// reach over a call (1/60 s) stays more than 10 cm from every board stone.
vg::RigidBodyState thrown() {
  const Quaterniond tilt(Eigen::AngleAxisd(0.3, Vector3d(0.6, 0.8, 0.0)));
  vg::RigidBodyState s =
      at(Vector3d(kHalfX + 0.14, 0.01, -kThickness + 0.1), tilt, Vector3d(0.3, 0.1, 0.5));
  return with_omega(s, Vector3d(1.0, -2.0, 20.0));
}

struct Trace {
  std::vector<vg::RigidBodyState> states;  // the thrown stone after each call
  vg::WorldCounters before, after;         // around the calls
  long calls = 0, awake_calls = 0;         // calls, and those that began with the stone awake
};

Trace throw_beside(vg::World& world, int calls) {
  std::vector<vg::WorldEvent> events;
  const double t0 = world.time();
  const vg::StoneId id = world.add_stone(0, thrown(), t0, events);
  Trace trace;
  trace.before = world.counters();
  for (int k = 1; k <= calls; ++k) {
    if (!world.is_resting(id)) ++trace.awake_calls;
    world.advance_to(t0 + k / 60.0, events);
    trace.states.push_back(world.state(id));
    ++trace.calls;
  }
  trace.after = world.counters();
  return trace;
}

long delta(const vg::WorldCounters& a, const vg::WorldCounters& b, long vg::WorldCounters::*f) {
  return b.*f - a.*f;
}

TEST(WorldRestingCost, A361StoneBoardAddsNoWorkToAStoneMovingBesideIt) {
  vg::World full = board_of(true);
  vg::World one = board_of(false);
  ASSERT_EQ(full.stone_count(), 361U);
  ASSERT_TRUE(full.all_resting());
  ASSERT_TRUE(one.all_resting());
  std::vector<vg::RigidBodyState> frozen;
  for (std::size_t i = 0; i < full.stone_count(); ++i) frozen.push_back(full.state(i));

  const int calls = 300;  // 5 s at 60 Hz: it bounces, slides and comes to rest
  const Trace a = throw_beside(full, calls);
  const Trace b = throw_beside(one, calls);
  ASSERT_GT(a.after.impacts - a.before.impacts, 0) << "the scene lost its bounce";
  ASSERT_GT(a.after.plane_contact_steps - a.before.plane_contact_steps, 0)
      << "the scene lost its sliding";

  // The same work, counted, with 361 or 1 resting stones.
  for (long vg::WorldCounters::*f :
       {&vg::WorldCounters::stones_visited, &vg::WorldCounters::broad_phase_tests,
        &vg::WorldCounters::pair_candidates, &vg::WorldCounters::pair_searches,
        &vg::WorldCounters::pair_gap_checks, &vg::WorldCounters::stages,
        &vg::WorldCounters::flight_steps, &vg::WorldCounters::events}) {
    EXPECT_EQ(delta(a.before, a.after, f), delta(b.before, b.after, f));
  }
  EXPECT_EQ(a.after.work() - a.before.work(), b.after.work() - b.before.work());
  // Only the moving stone is visited, once per call while it is awake; no resting stone is
  // ever a candidate (its reach meets none).
  EXPECT_EQ(delta(a.before, a.after, &vg::WorldCounters::stones_visited), a.awake_calls);
  EXPECT_EQ(delta(a.before, a.after, &vg::WorldCounters::pair_candidates), 0);
  EXPECT_GT(a.awake_calls, 10);

  // The same path, bit for bit, and the board frozen.
  for (int k = 0; k < calls; ++k) {
    EXPECT_TRUE(a.states[k] == b.states[k]) << "call " << k + 1;
  }
  for (std::size_t i = 0; i < frozen.size(); ++i) {
    EXPECT_TRUE(full.state(i) == frozen[i]) << "stone " << i;
    EXPECT_TRUE(full.is_resting(i)) << "stone " << i;
  }
}

// Resting everywhere: a call changes no counter but the calls and passes, whatever the count.
TEST(WorldRestingCost, AFullRestingBoardWithStoneContactCostsOnePassPerCall) {
  vg::World world = board_of(true);
  std::vector<vg::WorldEvent> events;
  const vg::WorldCounters before = world.counters();
  const long calls = 1000000;  // the 10^6
  for (long k = 1; k <= calls; ++k) world.advance_to(1e-3 + k * 1e-3, events);
  const vg::WorldCounters after = world.counters();
  EXPECT_EQ(after.advance_calls - before.advance_calls, calls);
  EXPECT_EQ(after.stages - before.stages, calls);
  EXPECT_EQ(after.stones_visited, before.stones_visited);
  EXPECT_EQ(after.broad_phase_tests, before.broad_phase_tests);
  EXPECT_EQ(after.pair_candidates, before.pair_candidates);
  EXPECT_EQ(after.work(), before.work());
  EXPECT_EQ(after.flight_steps, before.flight_steps);
  EXPECT_EQ(after.events, before.events);
  EXPECT_TRUE(events.empty());
}

}  // namespace
