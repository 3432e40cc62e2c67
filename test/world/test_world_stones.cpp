// The World's stone table (issue 15): stones of their own bodies (black 22.2 mm, white 21.9 mm),
// stable ids, adding, removing and clearing while the world runs, and a resting full board added
// stone by stone that costs nothing. References are written here: masses from the densities of
// the materials table and the lens volume, lowest points from the test's own lens support
// mapping, landing times in closed form.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <vector>

#include "support/convex_reference.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone_materials.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;
using vg::StoneColor;
using vg::StoneId;
using vg::WorldEventKind;

// Nihon Ki-in set: half widths, size 33 (9.2 mm) for both colours.
constexpr double kBlackA = 0.0111, kWhiteA = 0.01095, kHalfHeight = 0.0046;

double half_width(StoneColor color) { return color == StoneColor::black ? kBlackA : kWhiteA; }

// m = rho V, V = pi c (3 a^2 + c^2) / 3 (two spherical caps), rho from the materials table:
// black slate, white shell.
double mass_of(StoneColor color) {
  const double a = half_width(color), c = kHalfHeight;
  const double rho = vg::material_density(color == StoneColor::black ? "slate" : "shell");
  return rho * M_PI * c * (3 * a * a + c * c) / 3;
}

// How far the lens reaches below its centre with axis b, from the test's own support mapping.
double lowest_reach(StoneColor color, const Vector3d& b) {
  vgtest::LensReference l{half_width(color), kHalfHeight};
  l.b = b;
  return l.reach(Vector3d::UnitZ());
}

vg::RigidBodyState flat_at(const vg::WorldConfig& c, const char* point, double lift = 0.0) {
  const Vector3d p = vg::go_point_world(c.board, vg::parse_gtp_point(point));
  return at(Vector3d(p.x(), p.y(), kHalfHeight + lift));
}

// Black and white tilted 60 degrees fall from one height: each hits the board when its own
// lowest point (the rim, a sin 60 below the centre) has fallen to the top face,
// t = sqrt(2 (z0 - reach) / g), so the narrower white lands later; each stone's energy is its
// own mass's m g z0.
TEST(WorldStones, BlackAndWhiteFallWithTheirOwnMassesAndLandWithTheirOwnRadii) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  const double tilt = M_PI / 3, z0 = 0.05;
  const Quaterniond q(Eigen::AngleAxisd(tilt, Vector3d::UnitX()));
  const Vector3d b = q * Vector3d::UnitZ();
  const StoneId black =
      world.add_stone(StoneColor::black, at(Vector3d(-0.05, 0, z0), q), 0, events);
  const StoneId white = world.add_stone(StoneColor::white, at(Vector3d(0.05, 0, z0), q), 0, events);
  EXPECT_NE(black, white);
  EXPECT_TRUE(world.color(black) == StoneColor::black);
  EXPECT_TRUE(world.color(white) == StoneColor::white);
  EXPECT_NE(world.body_of(black), world.body_of(white));
  EXPECT_EQ(world.body_count(), 3u);  // the config's, black's, white's
  for (const StoneId id : {black, white}) {
    const StoneColor color = *world.color(id);
    EXPECT_NEAR(world.energy(id), mass_of(color) * kG * z0, 1e-15 * mass_of(color) * kG * z0);
  }
  EXPECT_GT(world.energy(black), world.energy(white));  // 5.08 g against 4.95 g

  for (double t = 1e-3; t <= 0.2; t += 1e-3) world.advance_to(t, events);
  for (const StoneId id : {black, white}) {
    const StoneColor color = *world.color(id);
    const double reach = lowest_reach(color, b);
    EXPECT_NEAR(reach, half_width(color) * std::sin(tilt), 1e-15);  // the rim is lowest
    const double t_hit = std::sqrt(2 * (z0 - reach) / kG);
    const vg::WorldEvent* first = nullptr;
    for (const vg::WorldEvent& e : events) {
      if (e.id == id && e.kind == WorldEventKind::impact) {
        first = &e;
        break;
      }
    }
    ASSERT_NE(first, nullptr) << vg::stone_id_name(id);
    EXPECT_NEAR(first->time_s, t_hit, 1e-12) << vg::stone_id_name(id);
    EXPECT_NEAR(first->approach_speed_mps, kG * t_hit, 1e-9);
    EXPECT_FALSE(first->other.has_value());  // the board, not a stone
    EXPECT_EQ(first->stone, world.index_of(id));
  }
  // White's rim is 0.13 mm higher: it lands later.
  const double dt_expected = std::sqrt(2 * (z0 - lowest_reach(StoneColor::white, b)) / kG) -
                             std::sqrt(2 * (z0 - lowest_reach(StoneColor::black, b)) / kG);
  EXPECT_GT(dt_expected, 1e-5);
}

// Add, remove and clear while stones fly: the survivors keep their ids and their motion, indices
// shift, a removed id is unknown afterwards and never given again.
TEST(WorldStones, AddRemoveAndClearDuringARun) {
  vg::World world = empty_world();
  const vg::WorldConfig& c = world.config();
  std::vector<vg::WorldEvent> events;
  const StoneId resting = world.add_stone(StoneColor::black, flat_at(c, "D4"), 0.0, events);
  // Set down resting: it rests at once, the event carries its id.
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, WorldEventKind::rest);
  EXPECT_EQ(events[0].id, resting);
  EXPECT_TRUE(world.is_resting(resting));
  const StoneId falling = world.add_stone(StoneColor::white, flat_at(c, "Q16", 0.02), 0.01, events);
  const StoneId doomed = world.add_stone(StoneColor::black, flat_at(c, "K10", 0.05), 0.01, events);
  EXPECT_EQ(world.stone_count(), 3u);
  EXPECT_EQ(world.stone_ids(), (std::vector<StoneId>{resting, falling, doomed}));
  world.advance_to(0.03, events);
  world.remove_stone(doomed, 0.04, events);
  EXPECT_FALSE(world.contains(doomed));
  EXPECT_EQ(world.stone_count(), 2u);
  EXPECT_EQ(field_of([&] { (void)world.state(doomed); }), "stone");
  const std::size_t after_removal = events.size();
  for (double t = 0.05; t <= 0.4; t += 1e-3) world.advance_to(t, events);
  for (std::size_t k = after_removal; k < events.size(); ++k) EXPECT_NE(events[k].id, doomed);
  // The falling white stone is untouched: it lands from 2 cm at the closed-form time.
  const vg::WorldEvent* hit = nullptr;
  for (const vg::WorldEvent& e : events) {
    if (e.id == falling && e.kind == WorldEventKind::impact) {
      hit = &e;
      break;
    }
  }
  ASSERT_NE(hit, nullptr);
  EXPECT_NEAR(hit->time_s, 0.01 + std::sqrt(2 * 0.02 / kG), 1e-12);
  EXPECT_EQ(world.index_of(falling), 1u);
  EXPECT_TRUE(world.is_resting(resting));

  world.clear(0.5);
  EXPECT_EQ(world.stone_count(), 0u);
  EXPECT_TRUE(world.all_resting());
  EXPECT_EQ(world.time(), 0.5);
  const StoneId next = world.add_stone(StoneColor::black, flat_at(c, "D4"), 0.5, events);
  EXPECT_LT(doomed, next);  // ids only grow
  EXPECT_TRUE(world.is_resting(next));
}

TEST(WorldStones, IdsAreNeverReused) {
  vg::World world = empty_world();
  const vg::WorldConfig& c = world.config();
  std::vector<vg::WorldEvent> events;
  std::set<StoneId> seen;
  double t = 0.0;
  for (int k = 0; k < 200; ++k) {
    const StoneId id =
        world.add_stone(k % 2 ? StoneColor::white : StoneColor::black, flat_at(c, "C3"), t, events);
    EXPECT_TRUE(seen.insert(id).second) << vg::stone_id_name(id);
    if (k % 3 != 0) world.remove_stone(id, t, events);
    if (k % 50 == 49) world.clear(t);
    t += 1e-3;
  }
  world.reset({flat_at(c, "D4")}, t);  // a reset's stones get new ids too
  EXPECT_TRUE(seen.insert(world.id(0)).second);
}

// 361 stones (alternating colours) added resting one by one, then 10^5 calls: nothing is looked
// at. Removing resting and awake stones keeps it so.
TEST(WorldStones, AFullBoardAddedStoneByStoneCostsNothing) {
  vg::World world = empty_world();
  const vg::WorldConfig& c = world.config();
  std::vector<vg::WorldEvent> events;
  for (int index = 0; index < vg::kGoLines * vg::kGoLines; ++index) {
    const vg::GoPoint p = vg::point_at_index(index);
    const Vector3d x = vg::go_point_world(c.board, p);
    world.add_stone((p.column + p.row) % 2 ? StoneColor::white : StoneColor::black,
                    at(Vector3d(x.x(), x.y(), kHalfHeight)), 0.0, events);
  }
  ASSERT_EQ(world.stone_count(), 361u);
  ASSERT_TRUE(world.all_resting());
  EXPECT_EQ(of_kind(events, WorldEventKind::rest).size(), 361u);
  std::vector<vg::RigidBodyState> frozen;
  for (const StoneId id : world.stone_ids()) frozen.push_back(world.state(id));
  const vg::WorldCounters before = world.counters();
  const std::size_t events_before = events.size();
  const long calls = 1000000;  // the 10^6
  for (long k = 1; k <= calls; ++k) world.advance_to(k * 1e-3, events);
  const vg::WorldCounters after = world.counters();
  EXPECT_EQ(after.advance_calls - before.advance_calls, calls);
  EXPECT_EQ(after.stones_visited, before.stones_visited);
  EXPECT_EQ(after.work(), before.work());
  EXPECT_EQ(after.flight_steps, before.flight_steps);
  EXPECT_EQ(after.events, before.events);
  EXPECT_EQ(events.size(), events_before);
  for (std::size_t i = 0; i < world.stone_count(); ++i) EXPECT_TRUE(world.state(i) == frozen[i]);

  // Wake one, remove it while it flies, remove a resting one: again nothing is visited.
  const StoneId tengen = world.id(vg::point_index(vg::parse_gtp_point("K10")));
  vg::RigidBodyState lifted = world.state(tengen);
  lifted.position_world.z() += 0.01;
  double t = world.time();
  world.set_state(tengen, lifted, t, events);
  EXPECT_FALSE(world.all_resting());
  world.remove_stone(tengen, t += 1e-3, events);
  world.remove_stone(world.id(0), t, events);
  EXPECT_TRUE(world.all_resting());
  EXPECT_EQ(world.stone_count(), 359u);
  const vg::WorldCounters removed = world.counters();
  for (int k = 0; k < 1000; ++k) world.advance_to(t += 1e-3, events);
  EXPECT_EQ(world.counters().stones_visited, removed.stones_visited);
  EXPECT_EQ(world.counters().work(), removed.work());
}

// Stones far apart cost what each costs alone (issue 15: an event's cost may grow at most as
// log N). 25 stones on every other point of the inner board (44 x 47.4 mm apart; far enough
// from the edges that no bound lets them fall to the table within a step), dropped flat
// from staggered heights (2 to 12 mm), every other one spinning: with stone contact on, no
// stone's bounce, contact phase or rest may end a pass for the others, so each advance_to is one
// pass and nothing is searched between stones; the motions are those of the world without stone
// contact, which advances each stone alone, bit for bit, event for event.
TEST(WorldStones, StonesFarApartCostWhatTheyCostAlone) {
  vg::WorldConfig with_contact = config(0.5);
  with_contact.stone_contact = true;
  vg::WorldConfig without_contact = config(0.5);
  without_contact.stone_contact = false;
  vg::World on(with_contact, std::vector<vg::RigidBodyState>{}, 0.0);
  vg::World off(without_contact, std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> events_on, events_off;
  int k = 0;
  for (int column = 5; column <= 13; column += 2) {
    for (int row = 5; row <= 13; row += 2, ++k) {
      const Vector3d x = vg::go_point_world(with_contact.board, vg::GoPoint{column, row});
      const double lift = 0.002 + 0.01 * std::fmod(0.6180339887498949 * (k + 1), 1.0);
      vg::RigidBodyState s = at(Vector3d(x.x(), x.y(), kHalfHeight + lift));
      const StoneColor color = k % 2 ? StoneColor::white : StoneColor::black;
      if (k % 2) s.angular_momentum_world = Vector3d(0, 0, 1e-7);  // spinning about its axis
      on.add_stone(color, s, 0.0, events_on);
      off.add_stone(color, s, 0.0, events_off);
    }
  }
  ASSERT_EQ(on.stone_count(), 25u);
  const vg::WorldCounters start = on.counters();
  const long calls = 90;  // 1.5 s at 1/60 s
  for (long n = 1; n <= calls; ++n) {
    on.advance_to(n / 60.0, events_on);
    off.advance_to(n / 60.0, events_off);
    for (std::size_t i = 0; i < on.stone_count(); ++i) {
      ASSERT_TRUE(on.state(i) == off.state(i))
          << "stone " << i << " at step " << n << ": " << on.state(i).position_world.transpose()
          << " / " << off.state(i).position_world.transpose() << " stages " << on.counters().stages
          << " pairs " << on.counters().pair_searches << " visited " << on.counters().stones_visited
          << " / " << off.counters().stones_visited;
    }
  }
  ASSERT_EQ(events_on.size(), events_off.size());
  for (std::size_t e = 0; e < events_on.size(); ++e) {
    EXPECT_EQ(events_on[e].time_s, events_off[e].time_s);
    EXPECT_EQ(events_on[e].stone, events_off[e].stone);
    EXPECT_TRUE(events_on[e].kind == events_off[e].kind);
  }
  EXPECT_GT(events_on.size(), 25u * 4);  // impacts and rests of every stone, at least
  const vg::WorldCounters& c = on.counters();
  EXPECT_EQ(c.stages - start.stages, calls);  // one pass per advance_to
  EXPECT_EQ(c.pair_searches, 0);
  EXPECT_EQ(c.pair_gap_checks, 0);
  EXPECT_EQ(c.pair_candidates, 0);
  EXPECT_GT(c.plane_contact_steps, 0);  // the spinning ones spun down on the board
  EXPECT_TRUE(on.all_resting());
}

// Bad input names the field and changes nothing.
TEST(WorldStones, BadInputChangesNothing) {
  vg::World world = empty_world();
  const vg::WorldConfig& c = world.config();
  std::vector<vg::WorldEvent> events;
  const StoneId a = world.add_stone(StoneColor::black, flat_at(c, "D4"), 0.0, events);
  const StoneId b = world.add_stone(StoneColor::white, flat_at(c, "E5", 0.01), 0.0, events);
  world.advance_to(0.01, events);
  const std::vector<StoneId> ids = world.stone_ids();
  const std::vector<vg::RigidBodyState> states{world.state(a), world.state(b)};
  const std::size_t bodies = world.body_count();
  const vg::WorldCounters counters = world.counters();
  const double time = world.time();
  const std::size_t n_events = events.size();
  const StoneId unknown{12345};
  vg::RigidBodyState nan_state = flat_at(c, "F6", 0.01);
  nan_state.velocity_world.x() = std::nan("");
  vg::RigidBodyState sunk = flat_at(c, "F6");
  sunk.position_world.z() -= 1e-3;  // 1 mm into the board
  vg::RigidBodyState moved = world.state(a);
  moved.position_world.x() += 1e-3;

  EXPECT_EQ(field_of([&] { world.remove_stone(unknown, time, events); }), "stone");
  EXPECT_EQ(field_of([&] { world.set_state(unknown, moved, time, events); }), "stone");
  EXPECT_EQ(field_of([&] { (void)world.mode(unknown); }), "stone");
  EXPECT_EQ(field_of([&] { (void)world.add_stone(StoneColor::black, nan_state, time, events); }),
            "state");
  EXPECT_EQ(field_of([&] { (void)world.add_stone(StoneColor::white, sunk, time, events); }),
            "state");
  EXPECT_EQ(field_of([&] { (void)world.add_stone(std::size_t{99}, moved, time, events); }), "body");
  EXPECT_EQ(field_of([&] { (void)world.add_stone(StoneColor::black, moved, time - 1, events); }),
            "time");
  EXPECT_EQ(field_of([&] { world.set_state(a, nan_state, time, events); }), "state");
  EXPECT_EQ(field_of([&] { world.remove_stone(a, std::nan(""), events); }), "time");
  EXPECT_EQ(field_of([&] { world.clear(time - 1); }), "time");
  EXPECT_EQ(field_of([&] { world.move_resting_stone(b, Eigen::Vector2d(0, 0), time, events); }),
            "stone");  // b is not resting yet
  EXPECT_EQ(field_of([&] { world.move_resting_stone(a, Eigen::Vector2d(0.3, 0), time, events); }),
            "position");  // off the top face
  EXPECT_EQ(field_of([&] {
              world.move_resting_stone(a, Eigen::Vector2d(std::nan(""), 0), time, events);
            }),
            "position");

  EXPECT_EQ(world.stone_ids(), ids);
  EXPECT_TRUE(world.state(a) == states[0]);
  EXPECT_TRUE(world.state(b) == states[1]);
  EXPECT_EQ(world.body_count(), bodies);
  EXPECT_EQ(world.time(), time);
  EXPECT_EQ(world.counters().work(), counters.work());
  EXPECT_EQ(events.size(), n_events);

  // A resting stone moved on the face stays resting and costs nothing.
  world.move_resting_stone(a, Eigen::Vector2d(0.01, 0.02), time, events);
  EXPECT_TRUE(world.is_resting(a));
  EXPECT_EQ(world.state(a).position_world, Vector3d(0.01, 0.02, states[0].position_world.z()));
}

}  // namespace
