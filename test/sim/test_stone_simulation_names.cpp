// Stones addressed by name in StoneSimulation: ~set_state and ~set_angular_velocity of a placed
// stone move that stone only (its fall after a teleport against the free-fall time sqrt(2 h / g),
// the others bit for bit still); an unknown or removed name is refused naming it and the stones
// there are, with nothing queued; ~remove and ~clear take the initial stone `stone` off too and
// ~reset puts it back; a set-down with no room is refused when asked, also when the layout that
// leaves no room is only queued (set-downs, or a drop that nudges).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "sim/sim_test_support.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/stone_states.h"
#include "virtual_go/world/stone_placement.h"

namespace vg = virtual_go;
using namespace simtest;

namespace {

void run(vg::StoneSimulation& sim, std::int64_t& now, std::int64_t duration_ns,
         std::vector<vg::SegmentEvent>& out) {
  const std::int64_t end = now + duration_ns;
  for (; now <= end; now += 10 * kMs) {
    const vg::UpdateResult r = sim.update(now);
    ASSERT_TRUE(r.error.empty()) << r.error;
    out.insert(out.end(), r.events.begin(), r.events.end());
  }
}

vg::PlaceRequest at(const std::string& point, const std::string& color) {
  vg::PlaceRequest r;
  r.point = point;
  r.color = color;
  return r;
}

std::string place(vg::StoneSimulation& sim, const vg::PlaceRequest& r) {
  std::string answer;
  return sim.place(r, answer);
}

const vg::StoneStateEntry* find(const std::vector<vg::StoneStateEntry>& entries,
                                const std::string& name) {
  for (const vg::StoneStateEntry& e : entries) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

bool same_bits(const vg::StateOutput& a, const vg::StateOutput& b) {
  return std::memcmp(a.position_world.data(), b.position_world.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(),
                     4 * sizeof(double)) == 0;
}

// The InvalidArgument a request throws: its field and message ("(accepted)" when none).
template <typename F>
std::pair<std::string, std::string> refusal(F&& f) {
  try {
    f();
  } catch (const vg::InvalidArgument& e) {
    return {e.field(), e.what()};
  }
  return {"(accepted)", ""};
}

}  // namespace

TEST(StoneSimulationNames, SetStateOfAPlacedStoneMovesThatStoneOnly) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  ASSERT_EQ(place(sim, at("D4", "black")), "black_1");
  ASSERT_EQ(place(sim, at("Q16", "white")), "white_1");
  run(sim, now, 3000 * kMs, events);  // the initial stone rests on K10 by now
  const std::vector<vg::StoneStateEntry> before = vg::stone_states(sim);
  const vg::StoneStateEntry* d4 = find(before, "black_1");
  ASSERT_NE(d4, nullptr);
  ASSERT_TRUE(d4->resting);
  ASSERT_TRUE(sim.resting());
  // Lifted by h above where it rests, flat, still: it falls h to the board.
  const double h = 0.03;
  const Eigen::Vector3d lifted = d4->output.position_world + Eigen::Vector3d(0.0, 0.0, h);
  events.clear();
  sim.set_state(lifted, Eigen::Vector4d(0, 0, 0, 1), Eigen::Vector3d::Zero(),
                Eigen::Vector3d::Zero(), "black_1");
  run(sim, now, 500 * kMs, events);
  const vg::SegmentEvent* set = nullptr;
  const vg::SegmentEvent* impact = nullptr;
  for (const vg::SegmentEvent& e : events) {
    EXPECT_EQ(e.stone, "black_1") << vg::event_reason_name(e.reason) << " of " << e.stone;
    if (e.reason == vg::EventReason::set_state) set = &e;
    if (e.reason == vg::EventReason::impact && !impact) impact = &e;
  }
  ASSERT_NE(set, nullptr);
  ASSERT_NE(impact, nullptr);
  EXPECT_EQ(set->state.position_world, lifted);
  const double fall_s = vg::seconds_between(set->stamp_ns, impact->stamp_ns) +
                        impact->time_offset_s - set->time_offset_s;
  EXPECT_NEAR(fall_s, std::sqrt(2.0 * h / kG), 1e-9);
  // The others never moved: bit for bit where they rested.
  const std::vector<vg::StoneStateEntry> after = vg::stone_states(sim);
  for (const char* name : {"stone", "white_1"}) {
    ASSERT_NE(find(after, name), nullptr) << name;
    EXPECT_TRUE(same_bits(find(after, name)->output, find(before, name)->output)) << name;
  }
}

TEST(StoneSimulationNames, SetAngularVelocityOfAPlacedStoneSpinsThatStone) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  ASSERT_EQ(place(sim, at("C3", "white")), "white_1");
  run(sim, now, 3000 * kMs, events);
  events.clear();
  // About its own axis, in its body frame named by its name: flat, so the same in the world.
  sim.set_angular_velocity(Eigen::Vector3d(0.0, 0.0, 5.0), "white_1", "white_1");
  run(sim, now, 20 * kMs, events);
  const vg::SegmentEvent* spun = nullptr;
  for (const vg::SegmentEvent& e : events) {
    if (e.reason == vg::EventReason::set_angular_velocity) spun = &e;
  }
  ASSERT_NE(spun, nullptr);
  EXPECT_EQ(spun->stone, "white_1");
  EXPECT_NEAR(spun->output.angular_velocity_world.z(), 5.0, 1e-12);
  EXPECT_NEAR(spun->output.angular_velocity_world.head<2>().norm(), 0.0, 1e-12);
  EXPECT_EQ(spun->state.velocity_world, Eigen::Vector3d::Zero());
  EXPECT_TRUE(sim.resting());  // the initial stone was not touched
}

TEST(StoneSimulationNames, AnUnknownNameIsRefusedNamingItAndTheStones) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  ASSERT_EQ(place(sim, at("D4", "black")), "black_1");
  const std::size_t pending = sim.pending_requests();
  const auto [field, message] = refusal([&] {
    sim.set_state(Eigen::Vector3d(0, 0, 0.1), Eigen::Vector4d(0, 0, 0, 1), Eigen::Vector3d::Zero(),
                  Eigen::Vector3d::Zero(), "black_9");
  });
  EXPECT_EQ(field, "name");
  EXPECT_NE(message.find("'black_9'"), std::string::npos) << message;
  EXPECT_NE(message.find("the stones are stone, black_1"), std::string::npos) << message;
  const auto spin =
      refusal([&] { sim.set_angular_velocity(Eigen::Vector3d(0, 0, 1), "world", "white_1"); });
  EXPECT_EQ(spin.first, "name");
  EXPECT_NE(spin.second.find("'white_1'"), std::string::npos) << spin.second;
  EXPECT_EQ(sim.pending_requests(), pending);
  // A stone waiting to be placed can be addressed already.
  EXPECT_EQ(refusal([&] {
              sim.set_angular_velocity(Eigen::Vector3d(0, 0, 1), "world", "black_1");
            }).first,
            "(accepted)");
}

TEST(StoneSimulationNames, ClearTakesTheInitialStoneTooAndResetPutsItBack) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  for (const char* p : {"C3", "D4"}) place(sim, at(p, "white"));
  run(sim, now, 20 * kMs, events);
  events.clear();
  sim.clear();
  run(sim, now, 20 * kMs, events);
  EXPECT_TRUE(vg::stone_states(sim).empty());
  EXPECT_FALSE(sim.initial_present());
  EXPECT_EQ(sim.world()->stone_count(), 0u);
  int cleared = 0;
  for (const vg::SegmentEvent& e : events) cleared += e.reason == vg::EventReason::clear;
  EXPECT_EQ(cleared, 3);
  // Gone: requests for it say so and how to bring it back; nothing queued.
  for (const std::string name : {"", "stone"}) {
    const auto [field, message] = refusal([&] {
      sim.set_state(Eigen::Vector3d(0, 0, 0.1), Eigen::Vector4d(0, 0, 0, 1),
                    Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), name);
    });
    EXPECT_EQ(field, "name");
    EXPECT_NE(message.find("'stone' is removed"), std::string::npos) << message;
    EXPECT_NE(message.find("~reset puts it back"), std::string::npos) << message;
    EXPECT_NE(message.find("there are no stones"), std::string::npos) << message;
  }
  std::string answer;
  EXPECT_EQ(refusal([&] { sim.remove("stone", answer); }).first, "name");
  EXPECT_EQ(sim.pending_requests(), 0u);
  // Nothing of it moves meanwhile (no auto reset either): the World has no stone to step.
  run(sim, now, 200 * kMs, events);
  EXPECT_TRUE(vg::stone_states(sim).empty());
  // ~reset: back at its initial state, where a fresh simulation starts it.
  events.clear();
  sim.reset();
  run(sim, now, 10 * kMs, events);
  ASSERT_TRUE(sim.initial_present());
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().reason, vg::EventReason::reset);
  EXPECT_EQ(events.front().stone, "stone");
  const vg::StoneSimulation fresh(board_scene());
  EXPECT_EQ(events.front().state.position_world, fresh.initial_state().position_world);
  const std::vector<vg::StoneStateEntry> entries = vg::stone_states(sim);
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].name, "stone");
  // ~remove by name takes it off alone.
  place(sim, at("E5", "black"));
  EXPECT_EQ(sim.remove("stone", answer), "stone");
  run(sim, now, 20 * kMs, events);
  ASSERT_EQ(vg::stone_states(sim).size(), 1u);
  EXPECT_EQ(vg::stone_states(sim)[0].name, "black_1");
}

// Set-downs at A1, again and again: each nudges the cluster outwards until one would push a stone
// off the board. Asked one step apart or all queued within one step, the same number are taken
// and the next one is refused at once ("point", "no room"), never accepted and dropped later.
TEST(StoneSimulationNames, NoRoomIsRefusedWhenAskedAlsoBehindQueuedPlacements) {
  const auto fill_a1 = [](bool step_between, int& accepted, std::string& refused,
                          std::size_t& on_board, std::string& last_answer) {
    vg::StoneSimulation sim(board_scene());
    std::int64_t now = kStart;
    std::vector<vg::SegmentEvent> events;
    run(sim, now, 10 * kMs, events);
    accepted = 0;
    for (int k = 0; k < 100 && refused.empty(); ++k) {
      try {
        std::string answer;
        sim.place(at("A1", "black"), answer);
        ++accepted;
        if (step_between) run(sim, now, 10 * kMs, events);
      } catch (const vg::InvalidArgument& e) {
        EXPECT_EQ(e.field(), "point");
        refused = e.what();
      }
    }
    run(sim, now, 20 * kMs, events);
    on_board = vg::stone_states(sim).size() - 1;  // the initial stone besides
    // The next answer carries no note of a placement the World refused.
    last_answer = sim.clear();
  };
  int stepped = 0, queued = 0;
  std::string refused_stepped, refused_queued, answer_stepped, answer_queued;
  std::size_t board_stepped = 0, board_queued = 0;
  fill_a1(true, stepped, refused_stepped, board_stepped, answer_stepped);
  fill_a1(false, queued, refused_queued, board_queued, answer_queued);
  ASSERT_FALSE(refused_stepped.empty()) << "A1 never ran out of room";
  EXPECT_NE(refused_stepped.find("no room at A1"), std::string::npos) << refused_stepped;
  // Two fit at A1 (the second nudges the first aside), the third would push one off the board.
  // A check that ignored the queue would take every one of the 100 queued requests.
  EXPECT_EQ(stepped, 2);
  EXPECT_EQ(queued, stepped);
  EXPECT_EQ(refused_queued, refused_stepped);
  EXPECT_EQ(board_stepped, static_cast<std::size_t>(stepped));
  EXPECT_EQ(board_queued, static_cast<std::size_t>(queued));
  EXPECT_EQ(answer_stepped, "applied at the next physics step");
  EXPECT_EQ(answer_queued, "applied at the next physics step");
}

// A set-down queued behind a drop in the same step is judged on the layout the drop leaves. Two
// blacks set down at C2 lie 11.1 mm either side of it (the second nudged the first), a white on
// A2. Alone, a black set down at A2 fits: the white is pushed 10.9 mm right and the new stone
// lies 11.1 mm left of A2, its centre 3 mm inside the board's left edge. A black dropped onto C2
// first finds no free spot and nudges its neighbours apart: the inner black comes to 21.9 mm
// from A2, touching the white (moved 0.19 mm left), so the set-down at A2 would push a stone off
// the top face. The answer when asked must be the answer when applied: drop_stone then
// set_down_stone on a World of the same board at one time, as apply_board_changes does (figures
// measured with them). Before a1e9aef the room check ignored queued drops: it took the set-down,
// which the World then refused ("was not placed").
TEST(StoneSimulationNames, ASetDownBehindANudgingDropGetsTheAnswerItsApplicationGets) {
  const auto set_up = [](vg::StoneSimulation& sim, std::int64_t& now) {
    std::vector<vg::SegmentEvent> events;
    run(sim, now, 10 * kMs, events);
    place(sim, at("C2", "black"));
    place(sim, at("C2", "black"));
    place(sim, at("A2", "white"));
    run(sim, now, 20 * kMs, events);
  };
  vg::PlaceRequest drop = at("C2", "black");
  drop.drop_height_m = 0.05;  // its ball (11.1 mm) far above a set-down's height band
  const auto field_of_refusal = [](vg::StoneSimulation& sim, const vg::PlaceRequest& r) {
    try {
      place(sim, r);
    } catch (const vg::InvalidArgument& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };

  // Without the drop there is room at A2.
  vg::StoneSimulation alone(board_scene());
  std::int64_t now = kStart;
  set_up(alone, now);
  EXPECT_EQ(field_of_refusal(alone, at("A2", "black")), "(accepted)");

  // Behind the drop, in the same step.
  vg::StoneSimulation sim(board_scene());
  now = kStart;
  set_up(sim, now);
  const std::vector<vg::StoneStateEntry> before = vg::stone_states(sim);
  EXPECT_EQ(place(sim, drop), "black_3");
  const std::string asked = field_of_refusal(sim, at("A2", "black"));
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  const std::vector<vg::StoneStateEntry> after = vg::stone_states(sim);
  // The drop nudged: the white on A2 moved towards the left edge (-x).
  ASSERT_NE(find(before, "white_1"), nullptr);
  ASSERT_NE(find(after, "white_1"), nullptr);
  EXPECT_LT(find(after, "white_1")->output.position_world.x(),
            find(before, "white_1")->output.position_world.x() - 1e-4);
  // Taken when asked means placed when applied, with no note of a refusal.
  if (asked == "(accepted)") {
    EXPECT_NE(find(after, "black_4"), nullptr) << "accepted when asked, refused when applied";
    EXPECT_EQ(sim.clear(), "applied at the next physics step");
  }

  // The application itself: the same requests on a World of the same board, at one time.
  vg::World world(*sim.world_config(), std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> world_events;
  for (const auto& [point, color] :
       {std::pair{"C2", vg::StoneColor::black}, std::pair{"C2", vg::StoneColor::black},
        std::pair{"A2", vg::StoneColor::white}}) {
    (void)vg::set_down_stone(world, color, vg::parse_gtp_point(point), 0.0, world_events);
  }
  const vg::PlacementResult dropped =
      vg::drop_stone(world, vg::StoneColor::black, vg::parse_gtp_point("C2"), drop.drop_height_m,
                     0.0, world_events);
  EXPECT_TRUE(dropped.nudged);
  std::string applied = "(accepted)";
  try {
    (void)vg::set_down_stone(world, vg::StoneColor::black, vg::parse_gtp_point("A2"), 0.0,
                             world_events);
  } catch (const vg::InvalidArgument& e) {
    applied = e.field();
  }
  EXPECT_EQ(applied, "point") << "the scene lost its point: the nudge leaves room at A2";
  EXPECT_EQ(asked, applied);
}
