// Issue 15: stones thrown into a full board. 361 stones set down at rest (checkered, as a game
// would leave them: row neighbours touch to ~1e-12 m, rows 1.5 mm apart), then one stone thrown
// or dropped at a point, advanced in 1 ms calls. Physics checked against physics at every call:
// the total energy never rises, no two stones nor a stone and the board overlap by more than
// 1e-9 m (an independent support-function bound, many_stones_support.h), everything comes to
// rest exactly (velocities exactly zero; stones no event named bitwise where they were set
// down). And it stays local: the stones woken (a `wake` event) and the largest island are those
// the throw really pushes, not the board; a join rule that spreads along the touching rows
// (every resting stone within reach of an island joins it) wakes all 362 (measured before the
// obstacle rule: Q16 in one island of 362 within 0.1 s; D4 woke all 361).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "virtual_go/go/go_point.h"
#include "virtual_go/world/stone_placement.h"
#include "world/many_stones_support.h"
#include "world/static_balance.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;

struct Throw {
  const char* name;
  const char* point;  // GTP name of the point it is thrown at (occupied: it lands on stones)
  double height_m;    // of the stone's lowest point above the set-down stones' pose
  Vector3d velocity_mps;
  std::size_t most_woken;  // a bound well below a board-wide island's 361
};

void PrintTo(const Throw& t, std::ostream* os) { *os << t.name; }

class WorldFullBoardThrow : public ::testing::TestWithParam<Throw> {};

TEST_P(WorldFullBoardThrow, WakesWhatItPushesNeverGainsEnergyNeverOverlapsAndRestsExactly) {
  const Throw& th = GetParam();
  vg::WorldConfig c = config(0.5);
  c.stone_contact = true;
  vg::World world(c, std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> events;
  for (int index = 0; index < vg::kGoLines * vg::kGoLines; ++index) {
    const vg::GoPoint p = vg::point_at_index(index);
    const vg::StoneColor colour =
        (p.column + p.row) % 2 == 0 ? vg::StoneColor::black : vg::StoneColor::white;
    (void)vg::set_down_stone(world, colour, p, 0.0, events);
  }
  double t = 1e-3;
  world.advance_to(t, events);
  ASSERT_TRUE(world.all_resting());
  const std::size_t board = world.stone_count();
  std::vector<vg::RigidBodyState> frozen;
  std::vector<StoneFacts> facts;
  for (std::size_t i = 0; i < board; ++i) {
    frozen.push_back(world.state(i));
    facts.push_back(facts_of(world, i));
  }
  const std::size_t first_event = events.size();
  const vg::PlacementResult thrown =
      vg::drop_stone(world, vg::StoneColor::black, vg::parse_gtp_point(th.point), th.height_m, t,
                     events, th.velocity_mps);
  const std::size_t n = world.stone_count();
  ASSERT_EQ(n, board + 1);
  facts.push_back(facts_of(world, world.index_of(thrown.id)));
  const auto energy_now = [&](std::size_t i) {
    return energy_of(facts[i], world.state(i), c.motion.gravity_world);
  };
  // Only changed stones' energies change: the total is kept as a running sum.
  std::vector<double> e(n);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) total += (e[i] = energy_now(i));
  const double drop_j =
      facts.back().mass_kg * (0.5 * th.velocity_mps.squaredNorm() + kG * (th.height_m + 0.01));
  double lowest = total, worst_rise = 0.0;
  double worst_gap = std::numeric_limits<double>::infinity(), worst_board = worst_gap;
  std::vector<vg::RigidBodyState> previous;
  for (std::size_t i = 0; i < n; ++i) previous.push_back(world.state(i));
  const vg::WorldCounters start = world.counters();
  long calls = 0;
  std::vector<bool> changed(n, false);
  std::set<std::size_t> woken;
  std::size_t scanned = first_event;
  const std::clock_t cpu_start = std::clock();
  // Rest within 1 s: the bounces off the board alone end within 2 e v / (g (1 - e)) = 0.41 s
  // (v <= 2 m/s at the first landing, e = 0.5) and a slide within v / (mu g) = 0.7 s
  // (mu = 0.3); stone impacts only take energy away.
  const long most_calls = 20000;
  while (!world.all_resting() && calls < most_calls) {
    world.advance_to(t += 1e-3, events);
    ++calls;
    for (std::size_t i = 0; i < n; ++i) changed[i] = !(world.state(i) == previous[i]);
    for (std::size_t i = 0; i < n; ++i) {
      if (!changed[i]) continue;
      const vg::RigidBodyState& s = world.state(i);
      const double ei = energy_now(i);
      total += ei - e[i];
      e[i] = ei;
      const vgtest::LensReference lens = lens_of(facts[i], s);  // its own colour's lens
      // Over the board its top face, else the table (the lens's lowest point; the board's
      // sides are not checked here).
      const bool over = std::abs(s.position_world.x()) < 0.5 * c.board.size_x_m &&
                        std::abs(s.position_world.y()) < 0.5 * c.board.size_y_m;
      worst_board = std::min(worst_board, lens.x.z() - lens.reach(Vector3d::UnitZ()) -
                                              (over ? c.board.top_z_m() : c.board.table_z_m()));
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || (j < i && changed[j])) continue;  // each pair once
        const vg::RigidBodyState& sj = world.state(j);
        if ((sj.position_world - s.position_world).norm() > facts[i].a_m + facts[j].a_m + 1e-6)
          continue;
        worst_gap =
            std::min(worst_gap, pair_gap_bound(lens_of(facts[i], s), lens_of(facts[j], sj)));
      }
      previous[i] = s;
    }
    for (; scanned < events.size(); ++scanned) {
      if (events[scanned].kind == vg::WorldEventKind::wake)
        woken.insert(world.index_of(events[scanned].id));
    }
    ASSERT_LE(woken.size(), th.most_woken) << "after " << calls << " ms";
    worst_rise = std::max(worst_rise, total - lowest);
    lowest = std::min(lowest, total);
  }
  const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const vg::WorldCounters end = world.counters();
  std::printf(
      "%s: rest after %ld ms, woken %zu (obstacle wakes %ld), largest island %ld, islands %ld, "
      "sub-steps %ld, passes %ld, smallest pair gap %.3g m, board %.3g m, energy rise %.3g J, "
      "cpu %.2f s (noisy)\n",
      th.name, calls, woken.size(), end.obstacle_wakes - start.obstacle_wakes, end.largest_island,
      end.islands_formed - start.islands_formed, end.nonsmooth_steps - start.nonsmooth_steps,
      end.stages - start.stages, worst_gap, worst_board, worst_rise, cpu_s);
  ASSERT_TRUE(world.all_resting()) << "not at rest after " << calls << " ms";
  // Energy never rises (the running sum's round-off: 1e-12 of the drop's energy).
  EXPECT_LE(worst_rise, 1e-12 * drop_j);
  EXPECT_LE(static_cast<std::size_t>(end.largest_island), th.most_woken + 1);
  EXPECT_GE(worst_gap, -1e-9);
  EXPECT_GE(worst_board, -1e-9);
  // Exact rest; stones no event named never moved.
  std::vector<bool> named(n, false);
  for (std::size_t k = first_event; k < events.size(); ++k) {
    named[world.index_of(events[k].id)] = true;
    if (events[k].other) named[world.index_of(*events[k].other)] = true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(world.state(i).velocity_world, Vector3d::Zero()) << "stone " << i;
    EXPECT_EQ(world.state(i).angular_momentum_world, Vector3d::Zero()) << "stone " << i;
    if (i < board && !named[i]) {
      EXPECT_TRUE(world.state(i) == frozen[i]) << "stone " << i;
    }
  }
  // The stones an event named are held by their contacts within the island's 1 nm margin, the
  // others fixed supports (static_balance.h). Measured 2026-11-30: 0 unheld in all four, largest
  // unheld wrench 1e-9 of m g (A10); without the islands' hold check (before) Q16 left 4 of 5,
  // D4 11 of 15, K10 1 of 11 and A10 11 of 61 unheld.
  std::vector<bool> moved(n, false);
  for (std::size_t i = 0; i < n; ++i) moved[i] = named[i] || i >= board;
  EXPECT_EQ(print_unheld("the stones that moved", world, kGravity, 1e-9, moved), 0);
}

// Bounds on the stones woken: measured (see the run's printout: 4, 14, 10 and 59 woken) with
// room, and far below the 361 a board-wide island wakes. Two heavier throws were measured on
// the obstacle rule's branch and are left out for their run time (about 95 s each here): H8
// across the rows at (0.2, -0.9, -0.4) m/s woke 69 (largest island 70, 59 s CPU) and K10 from
// 3 cm at (1.2, 0.9, -1.3) m/s woke 66 (largest island 67, 59 s CPU); both rested exactly with no
// energy rise and no overlap.
INSTANTIATE_TEST_SUITE_P(
    Throws, WorldFullBoardThrow,
    ::testing::Values(Throw{"Q16_oblique_1m_s", "Q16", 0.02, Vector3d(0.6, 0.0, -0.8), 12},
                      Throw{"D4_sideways_1m_s", "D4", 0.02, Vector3d(1.0, 0.0, 0.0), 30},
                      Throw{"K10_dropped", "K10", 0.02, Vector3d::Zero(), 25},
                      Throw{"A10_edge_inward", "A10", 0.02, Vector3d(0.7, 0.1, -0.7), 120}),
    [](const ::testing::TestParamInfo<Throw>& info) { return std::string(info.param.name); });

}  // namespace
