// Placing stones at Go points (world/stone_placement): set down at rest, nudging neighbours when
// there is no free pose, and dropped. Separation is checked with the lens-lens distance
// (geometry/lens_pair_distance), not with the disc formula the placement solves with; offsets
// against closed forms (two 22.2 mm stones 22 mm apart leave room for a third between them only
// sqrt(22.2^2 - 22^2) mm off the line).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "virtual_go/common/validation.h"
#include "virtual_go/geometry/lens_pair_distance.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/world/stone_placement.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;
using vg::GoPoint;
using vg::StoneColor;
using vg::StoneId;

constexpr double kBlackA = 0.0111, kWhiteA = 0.01095, kHalfHeight = 0.0046;

// The smallest lens-lens gap over every pair of stones whose centres are within reach.
double smallest_gap(const vg::World& world) {
  double worst = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < world.stone_count(); ++i) {
    for (std::size_t j = i + 1; j < world.stone_count(); ++j) {
      const vg::RigidBodyState &a = world.state(i), &b = world.state(j);
      if ((a.position_world - b.position_world).norm() > 0.03) continue;
      const vg::LensPairContact c =
          vg::lens_pair_distance(world.body_model(world.body_of(i)).lens(), vg::lens_pose(a),
                                 world.body_model(world.body_of(j)).lens(), vg::lens_pose(b));
      worst = std::min(worst, c.gap_m);
    }
  }
  return worst;
}

// Largest horizontal distance of a stone from the point it belongs to; every stone must still
// be nearest its own point.
double largest_offset(const vg::World& world, const std::vector<std::pair<StoneId, GoPoint>>& at) {
  double worst = 0.0;
  for (const auto& [id, point] : at) {
    const Vector3d x = world.state(id).position_world;
    const Vector3d p = vg::go_point_world(world.config().board, point);
    EXPECT_EQ(vg::nearest_go_point_name(world.config().board, x), vg::gtp_name(point));
    worst = std::max(worst, (x - p).head<2>().norm());
  }
  return worst;
}

void expect_all_resting_flat(const vg::World& world) {
  for (std::size_t i = 0; i < world.stone_count(); ++i) {
    const vg::RigidBodyState& s = world.state(i);
    EXPECT_TRUE(world.is_resting(i)) << i;
    EXPECT_NEAR(s.position_world.z(), kHalfHeight, 1e-15) << i;
    EXPECT_EQ(s.velocity_world, Vector3d::Zero());
    EXPECT_EQ(s.angular_momentum_world, Vector3d::Zero());
  }
}

// Columns in the order A, C, B, E, D, G, F, ...: every second stone goes between two.
std::vector<int> zigzag_columns() {
  std::vector<int> order{0};
  for (int c = 2; c < vg::kGoLines; c += 2) {
    order.push_back(c);
    order.push_back(c - 1);
  }
  return order;
}

TEST(StonePlacement, OnAnEmptyBoardExactlyOnTheIntersectionAtRest) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  const GoPoint k10 = vg::parse_gtp_point("K10");
  const vg::PlacementResult r = vg::set_down_stone(world, StoneColor::black, k10, 0.0, events);
  const Vector3d p = vg::go_point_world(world.config().board, k10);
  const vg::RigidBodyState& s = world.state(r.id);
  EXPECT_EQ(s.position_world.x(), p.x());
  EXPECT_EQ(s.position_world.y(), p.y());
  EXPECT_NEAR(s.position_world.z(), kHalfHeight, 1e-16);
  EXPECT_EQ(s.orientation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_TRUE(world.is_resting(r.id));
  EXPECT_EQ(r.offset_m, 0.0);
  EXPECT_FALSE(r.nudged);
  EXPECT_TRUE(r.moved.empty());
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, vg::WorldEventKind::rest);
  EXPECT_EQ(events[0].id, r.id);
}

// One row of 19 blacks, A, C, B, E, D, ...: a stone between two (22 mm away each, 22.2 mm wide)
// has a free pose sqrt(22.2^2 - 22^2) = 2.973 mm off the line (the circles' intersection), well
// within half a spacing: it goes there, nobody is nudged.
TEST(StonePlacement, ARowOfBlacksPlacedBetweenNeighbours) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  std::vector<std::pair<StoneId, GoPoint>> placed;
  for (const int column : zigzag_columns()) {
    const GoPoint p{column, 3};
    const vg::PlacementResult r = vg::set_down_stone(world, StoneColor::black, p, 0.0, events);
    EXPECT_FALSE(r.nudged);
    placed.emplace_back(r.id, p);
  }
  expect_all_resting_flat(world);
  const double gap = smallest_gap(world);
  EXPECT_GE(gap, -1e-12);
  const double offset = largest_offset(world, placed);
  const double between = std::sqrt(std::pow(2 * kBlackA, 2) - 0.022 * 0.022);
  EXPECT_NEAR(offset, between, 1e-9);
  std::printf("[ row of 19 blacks ] smallest gap %.3g m, largest offset %.6g mm\n", gap,
              offset * 1e3);
}

// The same row between two full rows of whites (21.9 mm, no overlap among them): a stone between
// two blacks has no free pose within half a spacing, so its neighbours are nudged along the row.
// The row is 18 x 0.2 mm longer than its points allow, so its ends must move out ~1.8 mm.
TEST(StonePlacement, ASandwichedRowNudgesItsNeighbours) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  std::vector<std::pair<StoneId, GoPoint>> placed;
  for (const int row : {8, 10}) {
    for (int column = 0; column < vg::kGoLines; ++column) {
      const GoPoint p{column, row};
      const vg::PlacementResult r = vg::set_down_stone(world, StoneColor::white, p, 0.0, events);
      EXPECT_EQ(r.offset_m, 0.0);
      placed.emplace_back(r.id, p);
    }
  }
  int nudges = 0, sweeps = 0;
  std::size_t moved = 0;
  for (const int column : zigzag_columns()) {
    const GoPoint p{column, 9};
    const vg::PlacementResult r = vg::set_down_stone(world, StoneColor::black, p, 0.0, events);
    nudges += r.nudged;
    sweeps = std::max(sweeps, r.sweeps);
    moved += r.moved.size();
    for (const vg::MovedStone& m : r.moved) {
      EXPECT_TRUE(world.is_resting(m.id));
      EXPECT_TRUE(world.state(m.id) == m.state);
    }
    placed.emplace_back(r.id, p);
  }
  EXPECT_EQ(nudges, 9);  // B, D, ..., S
  expect_all_resting_flat(world);
  const double gap = smallest_gap(world);
  EXPECT_GE(gap, -1e-12);
  const double offset = largest_offset(world, placed);
  EXPECT_GE(offset, 18 * 0.0002 / 2 * 0.99);  // the row's excess, shared by its two ends at least
  std::printf(
      "[ sandwiched row ] smallest gap %.3g m, largest offset %.6g mm, %zu moves, "
      "at most %d sweeps\n",
      gap, offset * 1e3, moved, sweeps);
}

// A full board, colours alternating, set down row by row: every stone rests flat, none overlaps.
TEST(StonePlacement, AFullBoardSetDownRestsWithoutOverlap) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  std::vector<std::pair<StoneId, GoPoint>> placed;
  for (int index = 0; index < vg::kGoLines * vg::kGoLines; ++index) {
    const GoPoint p = vg::point_at_index(index);
    const StoneColor color = (p.column + p.row) % 2 ? StoneColor::white : StoneColor::black;
    placed.emplace_back(vg::set_down_stone(world, color, p, 0.0, events).id, p);
  }
  ASSERT_EQ(world.stone_count(), 361u);
  EXPECT_TRUE(world.all_resting());
  expect_all_resting_flat(world);
  const double gap = smallest_gap(world);
  EXPECT_GE(gap, -1e-12);
  const double offset = largest_offset(world, placed);
  std::printf("[ full board ] smallest gap %.3g m, largest offset %.6g mm\n", gap, offset * 1e3);
}

// Dropped flat from 1 cm with no twist: the contact is under the centre, so the bounces are
// vertical and it comes to rest exactly over its point.
TEST(StonePlacement, ADroppedStoneBouncesVerticallyAndRestsAtItsPoint) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  const GoPoint d4 = vg::parse_gtp_point("D4");
  const Vector3d p = vg::go_point_world(world.config().board, d4);
  const vg::PlacementResult r = vg::drop_stone(world, StoneColor::white, d4, 0.01, 0.0, events);
  EXPECT_NEAR(r.state.position_world.z(), kHalfHeight + 0.01, 1e-16);
  double t = 0.0;
  while (!world.all_resting() && t < 5.0) world.advance_to(t += 1e-3, events);
  ASSERT_TRUE(world.is_resting(r.id));
  // The first impact at the closed-form time.
  const auto impacts = of_kind(events, vg::WorldEventKind::impact);
  ASSERT_FALSE(impacts.empty());
  EXPECT_NEAR(impacts[0].time_s, std::sqrt(2 * 0.01 / kG), 1e-12);
  for (const vg::WorldEvent& e : events) {
    EXPECT_NEAR(e.state.position_world.x(), p.x(), 1e-12);
    EXPECT_NEAR(e.state.position_world.y(), p.y(), 1e-12);
    EXPECT_NEAR(e.state.velocity_world.head<2>().norm(), 0.0, 1e-12);
  }
  const vg::RigidBodyState& s = world.state(r.id);
  EXPECT_NEAR(s.position_world.x(), p.x(), 1e-12);
  EXPECT_NEAR(s.position_world.y(), p.y(), 1e-12);
  EXPECT_NEAR(s.position_world.z(), kHalfHeight, 1e-12);

  // Onto the occupied point: allowed (physics, not rules); it lands on the resting stone
  // (test_world_contacts checks that landing).
  const vg::PlacementResult second = vg::drop_stone(world, StoneColor::black, d4, 0.02, t, events);
  EXPECT_TRUE(world.contains(second.id));
  EXPECT_EQ(world.stone_count(), 2u);
}

// Dropped between two blacks set down on C4 and E4 (22.2 mm stones on a 22 mm grid): aimed at
// the free spot, it falls and bounces straight down 2.97321 mm off the line (the closed form
// sqrt(22.2^2 - 22^2) mm) and rests there touching neither neighbour: over D4 itself it would
// land on both rims (0.1 mm of overlap along the row). With stone contact on (the default) the
// aim means no stone-stone contact ever happens, so the motion is the single stone's vertical
// bounce and the neighbours never move.
TEST(StonePlacement, ADroppedStoneAimsAtTheFreeSpotBesideItsNeighbours) {
  vg::World world = empty_world();
  ASSERT_TRUE(world.config().stone_contact);
  std::vector<vg::WorldEvent> events;
  const vg::PlacementResult c4 =
      vg::set_down_stone(world, StoneColor::black, vg::parse_gtp_point("C4"), 0.0, events);
  const vg::PlacementResult e4 =
      vg::set_down_stone(world, StoneColor::black, vg::parse_gtp_point("E4"), 0.0, events);
  const vg::RigidBodyState c4_state = world.state(c4.id), e4_state = world.state(e4.id);
  const GoPoint d4 = vg::parse_gtp_point("D4");
  const Vector3d p = vg::go_point_world(world.config().board, d4);
  const vg::PlacementResult r = vg::drop_stone(world, StoneColor::black, d4, 0.01, 0.0, events);
  EXPECT_TRUE(r.moved.empty());
  const double between = std::sqrt(std::pow(2 * kBlackA, 2) - 0.022 * 0.022);
  EXPECT_NEAR(r.state.position_world.x(), p.x(), 1e-12);
  EXPECT_NEAR(std::abs(r.state.position_world.y() - p.y()), between, 1e-9);
  double t = 0.0, gap = std::numeric_limits<double>::infinity();
  while (!world.all_resting() && t < 5.0) {
    world.advance_to(t += 1e-3, events);
    gap = std::min(gap, smallest_gap(world));
  }
  ASSERT_TRUE(world.is_resting(r.id));
  EXPECT_GE(gap, -1e-12);
  const vg::RigidBodyState& s = world.state(r.id);
  EXPECT_NEAR(s.position_world.x(), r.state.position_world.x(), 1e-12);
  EXPECT_NEAR(s.position_world.y(), r.state.position_world.y(), 1e-12);
  EXPECT_TRUE(world.state(c4.id) == c4_state);  // bitwise: never pushed (searched, 1e-12 m apart)
  EXPECT_TRUE(world.state(e4.id) == e4_state);
  std::printf("[ dropped between C4 and E4 ] %.6g mm off D4, smallest gap %.3g m\n",
              1e3 * (s.position_world - p).head<2>().norm(), gap);
}

// Dropped onto D4 between blacks on C4 and E4 and whites on D3 and D5: no free spot within half
// a spacing (the blacks need it 2.97 mm off the row, the whites leave 1.65 mm), so the resting
// neighbours are nudged apart as for a set-down, and it lands in the room made, touching none.
TEST(StonePlacement, ADroppedStoneNudgesItsNeighboursWhenThereIsNoFreeSpot) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  for (const char* p : {"C4", "E4"})
    (void)vg::set_down_stone(world, StoneColor::black, vg::parse_gtp_point(p), 0.0, events);
  for (const char* p : {"D3", "D5"})
    (void)vg::set_down_stone(world, StoneColor::white, vg::parse_gtp_point(p), 0.0, events);
  const vg::PlacementResult r =
      vg::drop_stone(world, StoneColor::black, vg::parse_gtp_point("D4"), 0.01, 0.0, events);
  EXPECT_TRUE(r.nudged);
  EXPECT_FALSE(r.moved.empty());
  // Each move is said: a rest event (detail nudge) carrying the stone's new pose.
  std::size_t nudge_events = 0;
  for (const vg::WorldEvent& e : events) {
    if (e.detail != vg::WorldEventDetail::nudge) continue;
    ++nudge_events;
    EXPECT_EQ(e.kind, vg::WorldEventKind::rest);
    EXPECT_EQ(e.state.position_world, world.state(e.id).position_world);
  }
  EXPECT_EQ(nudge_events, r.moved.size());
  double t = 0.0, gap = smallest_gap(world);
  EXPECT_GE(gap, -1e-12);
  while (!world.all_resting() && t < 5.0) {
    world.advance_to(t += 1e-3, events);
    gap = std::min(gap, smallest_gap(world));
  }
  ASSERT_TRUE(world.is_resting(r.id));
  EXPECT_GE(gap, -1e-12);
  std::printf("[ dropped into D4 between four ] %zu stones nudged, %.3g mm off D4, gap %.3g m\n",
              r.moved.size(), 1e3 * r.offset_m, gap);
}

TEST(StonePlacement, BadRequestsChangeNothing) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  const GoPoint d4 = vg::parse_gtp_point("D4");
  (void)vg::set_down_stone(world, StoneColor::black, d4, 0.0, events);
  world.advance_to(0.5, events);
  const std::vector<StoneId> ids = world.stone_ids();
  const std::size_t n_events = events.size();
  const double time = world.time();
  const StoneColor bad_color = static_cast<StoneColor>(7);
  EXPECT_EQ(field_of([&] {
              vg::set_down_stone(world, StoneColor::black, GoPoint{19, 0}, time, events);
            }),
            "point");
  EXPECT_EQ(field_of([&] {
              vg::drop_stone(world, StoneColor::white, GoPoint{0, -1}, 0.01, time, events);
            }),
            "point");
  EXPECT_EQ(field_of([&] { vg::set_down_stone(world, bad_color, d4, time, events); }), "color");
  EXPECT_EQ(field_of([&] { vg::drop_stone(world, bad_color, d4, 0.01, time, events); }), "color");
  EXPECT_EQ(field_of([&] { vg::drop_stone(world, StoneColor::black, d4, -0.01, time, events); }),
            "drop_height");
  EXPECT_EQ(
      field_of([&] { vg::drop_stone(world, StoneColor::black, d4, std::nan(""), time, events); }),
      "drop_height");
  EXPECT_EQ(field_of([&] {
              vg::drop_stone(world, StoneColor::black, d4, 0.01, time, events,
                             Vector3d(std::nan(""), 0, 0));
            }),
            "velocity");
  EXPECT_EQ(field_of([&] { vg::set_down_stone(world, StoneColor::black, d4, time - 1, events); }),
            "time");
  EXPECT_EQ(world.stone_ids(), ids);
  EXPECT_EQ(events.size(), n_events);
  EXPECT_EQ(world.time(), time);

  vg::WorldConfig no_board = config(0.5);
  no_board.board_enabled = false;
  vg::World free_world(no_board, std::vector<vg::RigidBodyState>{}, 0.0);
  EXPECT_EQ(field_of([&] { vg::set_down_stone(free_world, StoneColor::black, d4, 0.0, events); }),
            "board");
  EXPECT_EQ(free_world.stone_count(), 0u);
}

// Everything a World shows of itself, kept as bits: time, ids, bodies, each stone's state and
// mode, the work counter.
struct WorldSnapshot {
  std::vector<double> numbers;
  std::vector<std::uint64_t> ids;
  std::vector<int> modes;
  std::size_t bodies = 0;
  long work = 0;
  explicit WorldSnapshot(const vg::World& w) : bodies(w.body_count()), work(w.counters().work()) {
    numbers.push_back(w.time());
    for (std::size_t i = 0; i < w.stone_count(); ++i) {
      const vg::RigidBodyState& s = w.state(i);
      for (const double* v :
           {s.position_world.data(), s.velocity_world.data(), s.angular_momentum_world.data()}) {
        numbers.insert(numbers.end(), v, v + 3);
      }
      numbers.insert(numbers.end(), s.orientation.coeffs().data(),
                     s.orientation.coeffs().data() + 4);
      ids.push_back(w.id(i).value);
      modes.push_back(static_cast<int>(w.mode(i)));
    }
  }
  bool operator==(const WorldSnapshot& o) const {
    return numbers.size() == o.numbers.size() &&
           std::memcmp(numbers.data(), o.numbers.data(), numbers.size() * sizeof(double)) == 0 &&
           ids == o.ids && modes == o.modes && bodies == o.bodies && work == o.work;
  }
};

// Set down at A1 again and again: each nudges the cluster outwards until a stone would leave
// the top face. That refusal, asked at a later time, must leave the world bit for bit as it was
// (no advance to the later time, no stone moved or added, no event).
TEST(StonePlacement, NoRoomIsRefusedBeforeAnythingChanges) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  const GoPoint a1 = vg::parse_gtp_point("A1");
  std::string refusal;
  int placed = 0;
  for (; placed < 200 && refusal.empty(); ++placed) {
    try {
      (void)vg::set_down_stone(world, StoneColor::black, a1, world.time(), events);
    } catch (const vg::InvalidArgument& e) {
      EXPECT_EQ(e.field(), "point");
      refusal = e.what();
    }
  }
  ASSERT_FALSE(refusal.empty()) << "A1 never ran out of room in 200 set-downs";
  EXPECT_NE(refusal.find("no room at A1"), std::string::npos) << refusal;
  ASSERT_TRUE(world.all_resting());
  const WorldSnapshot before(world);
  const std::size_t n_events = events.size();
  const double later = world.time() + 0.25;
  EXPECT_EQ(field_of([&] { vg::set_down_stone(world, StoneColor::black, a1, later, events); }),
            "point");
  EXPECT_TRUE(WorldSnapshot(world) == before);
  EXPECT_EQ(events.size(), n_events);
  // The planner, asked alone, refuses the same and changes nothing either.
  EXPECT_EQ(field_of([&] {
              vg::plan_set_down(world, world.color_body(StoneColor::black), a1,
                                vg::plan_stones(world));
            }),
            "point");
  EXPECT_TRUE(WorldSnapshot(world) == before);
}

// A later placement time while a stone flies would plan the wrong layout (the flight moves on):
// refused ("time") before the advance, nothing changed.
TEST(StonePlacement, LaterTimeWhileAStoneMovesIsRefusedUnchanged) {
  vg::World world = empty_world();
  std::vector<vg::WorldEvent> events;
  (void)vg::drop_stone(world, StoneColor::white, vg::parse_gtp_point("Q16"), 0.05, 0.0, events);
  (void)world.color_body(StoneColor::black);
  ASSERT_FALSE(world.all_resting());
  const WorldSnapshot before(world);
  const std::size_t n_events = events.size();
  EXPECT_EQ(field_of([&] {
              vg::set_down_stone(world, StoneColor::black, vg::parse_gtp_point("D4"), 0.01, events);
            }),
            "time");
  EXPECT_TRUE(WorldSnapshot(world) == before);
  EXPECT_EQ(events.size(), n_events);
}

}  // namespace
