// Random two-stone impacts through the World (stone contact on, no board, gravity on), black and
// white stones in random poses, tumbling, aimed at each other: checked at every sampled state and
// at every impact against physics written here. Between impacts both fly in closed form, and an
// impact exchanges equal and opposite impulses at one point, so at every time t
//   P(t) = P0 + M g t,   L_O(t) = L_O(0) + M (x_G0 t + V_G0 t^2 / 2) x g
// (the centre of mass G of the pair falls freely whatever the impacts do); the total energy
// never rises; the lenses never overlap by more than 1e-9 m (proven lower bound of their signed
// distance, many_stones_support.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "world/many_stones_support.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;
using Eigen::Vector3d;

struct Totals {
  Vector3d momentum = Vector3d::Zero();
  Vector3d angular_momentum = Vector3d::Zero();  // about the origin
  double energy_j = 0.0;
  // Scales of the round-off: sum of |m v| and of |L| + |x| |m v| over the stones.
  double momentum_scale = 0.0, angular_scale = 0.0, energy_scale = 0.0;
};

Totals totals(const std::vector<StoneFacts>& f, const std::vector<vg::RigidBodyState>& s,
              const Vector3d& g) {
  Totals t;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Vector3d p = f[i].mass_kg * s[i].velocity_world;
    t.momentum += p;
    t.angular_momentum += angular_momentum_about_origin(f[i], s[i]);
    t.energy_j += energy_of(f[i], s[i], g);
    t.momentum_scale += p.norm();
    t.angular_scale += s[i].angular_momentum_world.norm() + s[i].position_world.norm() * p.norm();
    t.energy_scale += 0.5 * f[i].mass_kg * s[i].velocity_world.squaredNorm() +
                      0.5 * omega_of(f[i], s[i]).dot(s[i].angular_momentum_world) +
                      f[i].mass_kg * std::abs(g.dot(s[i].position_world));
  }
  return t;
}

// The worst figures over a set of worlds.
struct Worst {
  double momentum = 0.0, angular = 0.0, rise = 0.0, gap = 1.0, lost = 0.0;
  void merge(const Worst& w) {
    momentum = std::max(momentum, w.momentum);
    angular = std::max(angular, w.angular);
    rise = std::max(rise, w.rise);
    gap = std::min(gap, w.gap);
    lost = std::max(lost, w.lost);
  }
};

// Worlds in which every contact was an impact, and those in which a pair ended touching
// without approaching (below 1e-9 m/s) and the World made an island of it.
struct PairRuns {
  Worst impacts_only, with_island;
  int worlds = 0, with_impact = 0, double_impacts = 0, impacts = 0, samples = 0;
  int worlds_with_islands = 0;
  long islands = 0;
};

// speed_scale multiplies the closing speeds and the spins: in free fall the relative motion does
// not feel gravity, so the island's sub-step h meets the motion of speed_scale h at 1.
PairRuns random_pairs(const Vector3d& origin, int k_worlds, double speed_scale = 1.0) {
  PairRuns runs;
  std::mt19937 rng(15015);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto unit = [&] { return Vector3d(normal(rng), normal(rng), normal(rng)).normalized(); };
  const Vector3d g = kGravity;
  const int kWorlds = k_worlds;
  const double dt = 2e-3, t_end = 0.1;
  int& worlds = runs.worlds;
  while (worlds < kWorlds) {
    Worst w;
    vg::WorldConfig c = config();
    c.board_enabled = false;
    c.stone_contact = true;
    c.stone_material.restitution = worlds % 10 == 0 ? 1.0 : uniform(rng);
    c.stone_material.friction = worlds % 7 == 0 ? 0.0 : uniform(rng);
    vg::World world(c, std::vector<vg::RigidBodyState>{}, 0.0);
    const vg::StoneColor colours[2] = {
        uniform(rng) < 0.5 ? vg::StoneColor::black : vg::StoneColor::white,
        uniform(rng) < 0.5 ? vg::StoneColor::black : vg::StoneColor::white};
    std::vector<StoneFacts> f = {facts_of_body(world, world.color_body(colours[0])),
                                 facts_of_body(world, world.color_body(colours[1]))};
    // A near the origin, B 30-45 mm away aimed at A within about 8 mm, 0.3-2 m/s closing, both
    // tumbling at up to 40 rad/s, both falling.
    std::vector<vg::RigidBodyState> s(2);
    s[0].position_world = origin + 0.01 * Vector3d(normal(rng), normal(rng), normal(rng));
    s[1].position_world = s[0].position_world + (0.03 + 0.015 * uniform(rng)) * unit();
    const Vector3d aim = s[0].position_world + 0.008 * normal(rng) * unit();
    s[0].velocity_world = Vector3d(0.3 * normal(rng), 0.3 * normal(rng), normal(rng));
    s[1].velocity_world = s[0].velocity_world + speed_scale * (0.3 + 1.7 * uniform(rng)) *
                                                    (aim - s[1].position_world).normalized();
    for (int i = 0; i < 2; ++i) {
      s[i].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI * uniform(rng), unit()));
      s[i].angular_momentum_world =
          inertia_world(f[i], s[i].orientation) * (speed_scale * 40.0 * uniform(rng) * unit());
    }
    if (pair_gap_bound(lens_of(f[0], s[0]), lens_of(f[1], s[1])) < 1e-4) continue;  // draw again
    ++worlds;
    std::vector<vg::WorldEvent> events;
    world.add_stone(colours[0], s[0], 0.0, events);
    world.add_stone(colours[1], s[1], 0.0, events);
    const Totals t0 = totals(f, s, g);
    const double m_total = f[0].mass_kg + f[1].mass_kg;
    const Vector3d x_g0 =
        (f[0].mass_kg * s[0].position_world + f[1].mass_kg * s[1].position_world) / m_total;
    const Vector3d v_g0 = t0.momentum / m_total;
    double previous_energy = t0.energy_j;
    // Every state handed out (a sample, or the pair right after an impact) at time t.
    const auto check = [&](const std::vector<vg::RigidBodyState>& now, double t) {
      const Totals tt = totals(f, now, g);
      const Vector3d p_expected = t0.momentum + m_total * g * t;
      const Vector3d l_expected =
          t0.angular_momentum + m_total * (x_g0 * t + 0.5 * t * t * v_g0).cross(g);
      const double p_scale = t0.momentum_scale + tt.momentum_scale + m_total * g.norm() * t;
      const double l_scale = t0.angular_scale + tt.angular_scale;
      w.momentum = std::max(w.momentum, (tt.momentum - p_expected).norm() / p_scale);
      w.angular = std::max(w.angular, (tt.angular_momentum - l_expected).norm() / l_scale);
      const double scale = std::max(t0.energy_scale, tt.energy_scale);
      w.rise = std::max(w.rise, (tt.energy_j - previous_energy) / scale);
      previous_energy = std::min(previous_energy, tt.energy_j);
      w.lost = std::max(w.lost, (t0.energy_j - tt.energy_j) / t0.energy_scale);
      if ((now[1].position_world - now[0].position_world).norm() < f[0].a_m + f[1].a_m + 1e-6)
        w.gap = std::min(w.gap, pair_gap_bound(lens_of(f[0], now[0]), lens_of(f[1], now[1])));
    };
    int pair_impacts = 0;
    for (int k = 1; k * dt <= t_end + 1e-12; ++k) {
      const std::size_t before = events.size();
      world.advance_to(k * dt, events);
      // Each pair impact gives both stones an impact event at one time, naming the other.
      for (std::size_t e = before; e < events.size(); ++e) {
        const vg::WorldEvent& ea = events[e];
        if (ea.kind != vg::WorldEventKind::impact || !ea.other || ea.stone != 0) continue;
        const vg::WorldEvent* eb = nullptr;
        for (std::size_t o = before; o < events.size(); ++o) {
          if (events[o].kind == vg::WorldEventKind::impact && events[o].stone == 1 &&
              events[o].time_s == ea.time_s)
            eb = &events[o];
        }
        EXPECT_NE(eb, nullptr) << "world " << worlds << ": no partner impact at " << ea.time_s;
        if (!eb) continue;
        EXPECT_TRUE(eb->other && *eb->other == ea.id && *ea.other == eb->id);
        check({ea.state, eb->state}, ea.time_s);
        // The law's own figure (P . u- + P K P / 2): <= 0 to its round-off.
        EXPECT_LE(ea.energy_change_j, 1e-15 * t0.energy_scale);
        ++pair_impacts;
      }
      check({world.state(std::size_t{0}), world.state(std::size_t{1})}, k * dt);
      ++runs.samples;
    }
    EXPECT_EQ(pair_impacts, world.counters().pair_impacts);
    runs.islands += world.counters().islands_formed;
    const bool island = world.counters().islands_formed > 0;
    runs.worlds_with_islands += island;
    (island ? runs.with_island : runs.impacts_only).merge(w);
    runs.impacts += pair_impacts;
    runs.with_impact += pair_impacts > 0;
    runs.double_impacts += pair_impacts > 1;
  }
  const auto line = [](const char* what, const Worst& w) {
    std::printf(
        "[ measured ]   %s: momentum error %.3g, angular momentum error %.3g (relative, against "
        "P0 + M g t and the free fall of the centre of mass); largest energy rise %.3g of E "
        "(largest loss %.3g); smallest pair gap bound %.3g m\n",
        what, w.momentum, w.angular, w.rise, w.lost, w.gap);
  };
  std::printf(
      "[ measured ] %d random black/white pairs through the World (centres near (%g, %g, %g), "
      "no board, speeds x %g): %d collided (%d more than once, %d pair impacts), %d samples; %d "
      "worlds formed islands (%ld)\n",
      runs.worlds, origin.x(), origin.y(), origin.z(), speed_scale, runs.with_impact,
      runs.double_impacts, runs.impacts, runs.samples, runs.worlds_with_islands, runs.islands);
  line("impacts only", runs.impacts_only);
  line("with an island", runs.with_island);
  return runs;
}

// 0.5 m above where the board would be (it is switched off). The worlds in which every contact
// was an impact, and those with an island.
TEST(WorldPairImpacts, RandomFlightsConserveMomentumNeverGainEnergyNorOverlap) {
  const PairRuns runs = random_pairs(Vector3d(0, 0, 0.5), 1000);
  EXPECT_GT(runs.with_impact, 900);
  EXPECT_GT(runs.worlds - runs.worlds_with_islands, 700);
  const Worst& w = runs.impacts_only;
  EXPECT_LT(w.momentum, 1e-14);
  EXPECT_LT(w.angular, 1e-14);
  EXPECT_LE(w.rise, 1e-14);
  EXPECT_GE(w.gap, -1e-9);
  EXPECT_LE(runs.with_island.rise, 1e-14);  // the energy never rises, islands or not
  // Those with an island (a pair that ends touching): no overlap, angular momentum kept (the
  // momentum: RandomFlightsThatEndTouchingKeepMomentumToRoundOff below). Before: overlap 4.3e-4 m,
  // errors 4.5e-4 and 8.7e-5.
  EXPECT_GE(runs.with_island.gap, -1e-9);
  EXPECT_LT(runs.with_island.angular, 1e-14);
}

// The same pairs at the origin, where the board's box would be, in a world whose board is
// switched off: the islands that touching pairs form meet only each other (IslandBody's
// board_enabled). Before, they held their members against the absent board and table: 1660
// islands instead of 186, momentum error 0.99, angular momentum error 2.9, overlap 4.3e-4 m.
TEST(WorldPairImpacts, RandomFlightsWhereTheSwitchedOffBoardWouldBe) {
  const PairRuns runs = random_pairs(Vector3d::Zero(), 1000);
  EXPECT_EQ(runs.islands, runs.worlds_with_islands);  // one island per such world, as at 0.5 m
  const Worst& w = runs.with_island;
  EXPECT_LT(w.angular, 1e-14);
  EXPECT_GE(w.gap, -1e-9);
}

// The worlds with an island, at 0.5 m and at the origin: the island keeps momentum and angular
// momentum (pair impulses and corrections equal and opposite, its energy guard scaling only the
// motion beyond the island's rigid motion) and sets them to the closed form of its centre of
// mass's free fall at every 0.1 ms sub-step (world/nonsmooth_island.h), so its round-off does
// not add up over the sub-steps; and its energy never exceeds the lowest it has had by more than
// one evaluation's round-off (nor its energy at formation). Before: it re-integrated every member
// each sub-step and the round-off added up, momentum errors 1.14e-14 and 1.15e-14, angular
// momentum 9.4e-15 and 9.3e-15 (relative), energy rises 4.8e-15 and 1.48e-14 of E.
TEST(WorldPairImpacts, RandomFlightsThatEndTouchingKeepMomentumToRoundOff) {
  for (const Vector3d& origin : {Vector3d(0, 0, 0.5), Vector3d(Vector3d::Zero())}) {
    const PairRuns runs = random_pairs(origin, 1000);
    EXPECT_GT(runs.worlds_with_islands, 100);
    EXPECT_LT(runs.with_island.momentum, 2e-15);
    EXPECT_LT(runs.with_island.angular, 2e-15);
    EXPECT_LE(runs.with_island.rise, 1e-14);
  }
}

// The same at ten times the speeds and spins: the island's 0.1 ms sub-step meets them as a 1 ms
// one meets the pairs above. Its samples between lattice points keep the closed-form momentum
// and angular momentum. Before, a sample whose partial sub-step lost more energy than the whole
// sub-step (the next lattice state's energy above it, by up to 10 % of the motion beyond the rigid
// one at 1 ms, or above the previous lattice state's by round-off) was scaled as a whole or
// replaced by the next lattice state: momentum errors 1.3e-4 and 8.1e-4, angular momentum 1.5e-5
// and 4.8e-4.
TEST(WorldPairImpacts, FastRandomFlightsThatEndTouchingKeepMomentumInEverySample) {
  for (const Vector3d& origin : {Vector3d(0, 0, 0.5), Vector3d(Vector3d::Zero())}) {
    const PairRuns runs = random_pairs(origin, 1000, 10.0);
    EXPECT_GT(runs.worlds_with_islands, 50);
    EXPECT_LT(runs.with_island.momentum, 2e-15);
    EXPECT_LT(runs.with_island.angular, 2e-15);
    EXPECT_LE(runs.with_island.rise, 1e-14);
    EXPECT_GE(runs.with_island.gap, -1e-9);
  }
}

}  // namespace

// Two flat stones sliding in one plane meet rim to rim (black into a resting white, no board, no
// gravity). The scene is symmetric under the reflection through that plane, so the outcome must
// be too: no vertical velocity, no angular momentum about a horizontal axis. And an impact at its
// exact time cannot depend on how far apart the stones started. Sharp rims touch along every tilt
// of their fans (the distance's normal there is round-off: before, 0.05 deg to 29 deg for the
// same collision started 3.1 or 0.75 mm apart, vertical speeds up to 0.028 m/s).
TEST(WorldPairImpacts, FlatStonesMeetingRimToRimInOnePlanePushInThatPlane) {
  for (const double speed : {0.3, 1.0}) {
    for (const double offset : {0.0, 0.5, 0.8}) {  // across, in units of the touching distance
      std::vector<vg::RigidBodyState> first;
      for (const double start_gap : {1e-5, 0.75e-3, 3.125e-3, 12.5e-3}) {
        vg::WorldConfig c = config();
        c.motion.gravity_world = Vector3d::Zero();
        c.board_enabled = false;
        c.stone_contact = true;
        vg::World world(c, std::vector<vg::RigidBodyState>{}, 0.0);
        const std::size_t black = world.color_body(vg::StoneColor::black);
        const std::size_t white = world.color_body(vg::StoneColor::white);
        const double touch = world.body_model(black).lens().half_width() +
                             world.body_model(white).lens().half_width();
        const double b = offset * touch;
        std::vector<vg::RigidBodyState> s(2);
        s[0].position_world = Vector3d(-(std::sqrt(touch * touch - b * b) + start_gap), 0.0, 0.0);
        s[0].velocity_world = Vector3d(speed, 0.0, 0.0);
        s[1].position_world = Vector3d(0.0, b, 0.0);
        std::vector<vg::WorldEvent> events;
        world.add_stone(vg::StoneColor::black, s[0], 0.0, events);
        world.add_stone(vg::StoneColor::white, s[1], 0.0, events);
        // To just after the impact (the stones then fly apart).
        world.advance_to(start_gap / speed + 1e-3, events);
        ASSERT_EQ(world.counters().pair_impacts, 1) << speed << " m/s, offset " << offset;
        const std::vector<vg::RigidBodyState> after = {world.state(0), world.state(1)};
        for (const vg::RigidBodyState& a : after) {
          EXPECT_LE(std::abs(a.velocity_world.z()), 1e-12)
              << speed << " " << offset << " " << start_gap;
          EXPECT_LE(a.angular_momentum_world.head<2>().norm(), 1e-18)
              << speed << " " << offset << " " << start_gap;
        }
        if (first.empty()) {
          first = after;
          continue;
        }
        for (int i = 0; i < 2; ++i) {
          EXPECT_LE((after[i].velocity_world - first[i].velocity_world).norm(), 1e-12 * speed)
              << speed << " " << offset << " " << start_gap;
        }
      }
    }
  }
}
