// ~place, ~remove and ~clear in StoneSimulation: stones named once and never again, set down flat
// on their intersection (lowest point on the board's top face), dropped stones whose first impact
// comes after the free-fall time sqrt(2 h / g), removal by name or by point, clear, and bad
// requests refused by field with nothing changed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sim/sim_test_support.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/stone_states.h"

namespace vg = virtual_go;
using namespace simtest;

namespace {

struct Events {
  std::vector<vg::SegmentEvent> events;
};

void run(vg::StoneSimulation& sim, std::int64_t& now, std::int64_t duration_ns, Events& out) {
  const std::int64_t end = now + duration_ns;
  for (; now <= end; now += 10 * kMs) {
    const vg::UpdateResult r = sim.update(now);
    ASSERT_TRUE(r.error.empty()) << r.error;
    for (const vg::SegmentEvent& e : r.events) out.events.push_back(e);
  }
}

const vg::StoneStateEntry* find(const std::vector<vg::StoneStateEntry>& entries,
                                const std::string& name) {
  for (const vg::StoneStateEntry& e : entries) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

vg::PlaceRequest at(const std::string& point, const std::string& color, double drop_m = 0.0) {
  vg::PlaceRequest r;
  r.point = point;
  r.color = color;
  r.drop_height_m = drop_m;
  return r;
}

std::string place(vg::StoneSimulation& sim, const vg::PlaceRequest& r) {
  std::string answer;
  return sim.place(r, answer);
}

std::string field_of_refusal(vg::StoneSimulation& sim, const vg::PlaceRequest& r) {
  try {
    place(sim, r);
  } catch (const vg::InvalidArgument& e) {
    return e.field();
  }
  return "(accepted)";
}

}  // namespace

TEST(StoneSimulationPlace, SetDownStonesLieFlatOnTheirPointsAndRest) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  EXPECT_EQ(place(sim, at("D4", "black")), "black_1");
  EXPECT_EQ(place(sim, at("q16", "white")), "white_1");
  run(sim, now, 30 * kMs, r);
  const std::vector<vg::StoneStateEntry> entries = vg::stone_states(sim);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].name, "stone");
  const vg::BoardGeometry& board = sim.world_config()->board;
  for (const auto& [name, point] : {std::pair{"black_1", "D4"}, std::pair{"white_1", "Q16"}}) {
    const vg::StoneStateEntry* e = find(entries, name);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_EQ(e->point, point);
    EXPECT_TRUE(e->resting);
    // No neighbour: exactly on the intersection, its lowest point (half its height below the
    // centre of a flat symmetric lens) on the top face, at rest.
    const Eigen::Vector3d p = vg::go_point_world(board, vg::parse_gtp_point(point));
    EXPECT_NEAR(e->output.position_world.x(), p.x(), 1e-12);
    EXPECT_NEAR(e->output.position_world.y(), p.y(), 1e-12);
    EXPECT_NEAR(e->output.position_world.z() - 0.5 * e->height_m, p.z(), 1e-9);
    EXPECT_EQ(e->output.velocity_world.norm(), 0.0);
  }
  EXPECT_EQ(find(entries, "black_1")->color, "black");
  EXPECT_EQ(find(entries, "white_1")->color, "white");
  // Black slate is wider than white shell (22.2 vs 21.9 mm, the default set).
  EXPECT_GT(find(entries, "black_1")->width_m, find(entries, "white_1")->width_m);
  // Each announced by a place event naming it, then its rest.
  int placed = 0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    if (r.events[i].reason != vg::EventReason::place) continue;
    ++placed;
    ASSERT_LT(i + 1, r.events.size());
    EXPECT_EQ(r.events[i + 1].reason, vg::EventReason::rest);
    EXPECT_EQ(r.events[i + 1].stone, r.events[i].stone);
  }
  EXPECT_EQ(placed, 2);
}

TEST(StoneSimulationPlace, NamesAreNeverReusedAndRemoveTakesANameOrAPoint) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  EXPECT_EQ(place(sim, at("A1", "black")), "black_1");
  EXPECT_EQ(place(sim, at("T19", "black")), "black_2");
  EXPECT_EQ(place(sim, at("F16", "white")), "white_1");
  run(sim, now, 20 * kMs, r);
  std::string answer;
  EXPECT_EQ(sim.remove("black_1", answer), "black_1");
  EXPECT_EQ(sim.remove("f16", answer), "white_1");  // by point
  run(sim, now, 20 * kMs, r);
  std::vector<vg::StoneStateEntry> entries = vg::stone_states(sim);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].name, "black_2");
  EXPECT_EQ(place(sim, at("A1", "black")), "black_3");
  EXPECT_EQ(place(sim, at("F16", "white")), "white_2");
  // A point whose stone is still waiting to be placed: that stone.
  EXPECT_EQ(sim.remove("F16", answer), "white_2");
  run(sim, now, 20 * kMs, r);
  entries = vg::stone_states(sim);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[2].name, "black_3");
  int removed = 0;
  for (const vg::SegmentEvent& e : r.events) removed += e.reason == vg::EventReason::remove;
  EXPECT_EQ(removed, 3);
  // Refused by name, nothing queued.
  const std::size_t pending = sim.pending_requests();
  for (const std::string bad : {"black_1", "stone_2", "C3", "Z1", ""}) {
    try {
      sim.remove(bad, answer);
      ADD_FAILURE() << bad << " accepted";
    } catch (const vg::InvalidArgument& e) {
      EXPECT_EQ(e.field(), "name") << bad;
    }
  }
  EXPECT_EQ(sim.pending_requests(), pending);
}

TEST(StoneSimulationPlace, ClearRemovesEveryStoneTheInitialOneToo) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  for (const char* p : {"C3", "D4", "E5"}) place(sim, at(p, "white"));
  run(sim, now, 20 * kMs, r);
  sim.clear();
  run(sim, now, 20 * kMs, r);
  EXPECT_TRUE(vg::stone_states(sim).empty());
  int cleared = 0;
  for (const vg::SegmentEvent& e : r.events) cleared += e.reason == vg::EventReason::clear;
  EXPECT_EQ(cleared, 4);
  EXPECT_EQ(place(sim, at("C3", "white")), "white_4");
}

TEST(StoneSimulationPlace, ADroppedStoneHitsTheBoardAfterTheFreeFallTime) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  const double h = 0.05;
  ASSERT_EQ(place(sim, at("O5", "black", h)), "black_1");
  run(sim, now, 1000 * kMs, r);
  const vg::SegmentEvent* placed = nullptr;
  const vg::SegmentEvent* impact = nullptr;
  for (const vg::SegmentEvent& e : r.events) {
    if (e.stone != "black_1") continue;
    if (e.reason == vg::EventReason::place) placed = &e;
    if (e.reason == vg::EventReason::impact && !impact) impact = &e;
  }
  ASSERT_NE(placed, nullptr);
  ASSERT_NE(impact, nullptr);
  const double fall_s = vg::seconds_between(placed->stamp_ns, impact->stamp_ns) +
                        impact->time_offset_s - placed->time_offset_s;
  EXPECT_NEAR(fall_s, std::sqrt(2.0 * h / kG), 1e-9);
  const vg::StoneStateEntry* e = find(vg::stone_states(sim), "black_1");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->point, "O5");
}

TEST(StoneSimulationPlace, BadRequestsAreRefusedByFieldAndChangeNothing) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(field_of_refusal(sim, at("D4", "red")), "color");
  EXPECT_EQ(field_of_refusal(sim, at("I5", "black")), "point");  // columns skip I
  EXPECT_EQ(field_of_refusal(sim, at("A20", "black")), "point");
  EXPECT_EQ(field_of_refusal(sim, at("D4", "black", -0.001)), "drop_height");
  EXPECT_EQ(field_of_refusal(sim, at("D4", "black", nan)), "drop_height");
  EXPECT_EQ(field_of_refusal(sim, at("D4", "black", vg::kMaxDropHeightM * 1.01)), "drop_height");
  vg::PlaceRequest fast = at("D4", "black", 0.01);
  fast.velocity_world = Eigen::Vector3d(1e6, 0.0, 0.0);
  EXPECT_EQ(field_of_refusal(sim, fast), "twist.linear");
  vg::PlaceRequest inside;  // by pose: the centre on the top face overlaps the board
  inside.color = "white";
  inside.position_world = vg::go_point_world(sim.world_config()->board, {3, 3});
  EXPECT_EQ(field_of_refusal(sim, inside), "pose.position");
  EXPECT_EQ(sim.pending_requests(), 0u);
  // No number was spent on a refused request.
  EXPECT_EQ(place(sim, at("D4", "black")), "black_1");
}

TEST(StoneSimulationPlace, AStoneByPoseFlies) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  vg::PlaceRequest above;
  above.color = "white";
  above.position_world =
      vg::go_point_world(sim.world_config()->board, {4, 14}) + Eigen::Vector3d(0, 0, 0.1);
  EXPECT_EQ(place(sim, above), "white_1");
  run(sim, now, 20 * kMs, r);
  const vg::StoneStateEntry* e = find(vg::stone_states(sim), "white_1");
  ASSERT_NE(e, nullptr);
  EXPECT_FALSE(e->resting);
  EXPECT_LT(e->output.velocity_world.z(), 0.0);  // falling
}

TEST(StoneSimulationPlace, StonesOutliveATimeJump) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  Events r;
  run(sim, now, 10 * kMs, r);
  place(sim, at("D4", "black"));
  run(sim, now, 20 * kMs, r);
  // ROS time jumps back (a bag loop): the World restarts; the stone stays where it lies.
  const Eigen::Vector3d before = find(vg::stone_states(sim), "black_1")->output.position_world;
  now = kStart - 5000 * kMs;
  run(sim, now, 20 * kMs, r);
  const vg::StoneStateEntry* e = find(vg::stone_states(sim), "black_1");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->output.position_world, before);
  EXPECT_TRUE(e->resting);
}

TEST(StoneSimulationPlace, WithoutTheBoardPlaceIsRefused) {
  vg::StoneConfig c = board_scene();
  c.board_enabled = false;
  vg::StoneSimulation sim(c);
  EXPECT_THROW(place(sim, at("D4", "black")), vg::RequestRefused);
  std::string answer;
  EXPECT_THROW(sim.remove("D4", answer), vg::RequestRefused);
  EXPECT_THROW(sim.clear(), vg::RequestRefused);
}
