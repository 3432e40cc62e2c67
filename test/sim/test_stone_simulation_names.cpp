// Stones addressed by name in StoneSimulation: ~set_state and ~set_angular_velocity of a placed
// stone move that stone only (its fall after a teleport against the free-fall time sqrt(2 h / g),
// the others bit for bit still); an unknown or removed name is refused naming it and the stones
// there are, with nothing queued; ~remove and ~clear take the initial stone `stone` off too and
// ~reset puts it back; a set-down with no room is refused when asked, also when the layout that
// leaves no room is only queued (set-downs, or a drop that nudges).
#include <gtest/gtest.h>

#include <algorithm>
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

namespace {

// How a black set-down at `point` is answered after `base` (set down, at rest): alone; when
// asked behind `drop` queued in the same step (and whether, taken, it was placed when applied);
// and by the application itself: drop_stone then set_down_stone on a World of the same board at
// one time, as apply_board_changes does. "(accepted)" or the refusal's field.
struct SetDownAnswers {
  std::string alone, asked, applied;
  bool placed = false;        // asked "(accepted)" and on the board after the step, no note
  double base_moved_m = 0.0;  // largest horizontal move of a base stone in that step
};

SetDownAnswers set_down_answers(const std::vector<std::pair<std::string, std::string>>& base,
                                const vg::PlaceRequest& drop, const std::string& point) {
  const auto field_of_refusal = [](vg::StoneSimulation& sim, const vg::PlaceRequest& r) {
    try {
      place(sim, r);
    } catch (const vg::InvalidArgument& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  const auto set_up = [&](vg::StoneSimulation& sim, std::int64_t& now) {
    std::vector<vg::SegmentEvent> events;
    run(sim, now, 10 * kMs, events);
    for (const auto& [p, color] : base) place(sim, at(p, color));
    run(sim, now, 20 * kMs, events);
  };
  SetDownAnswers a;
  vg::StoneSimulation alone(board_scene());
  std::int64_t now = kStart;
  set_up(alone, now);
  a.alone = field_of_refusal(alone, at(point, "black"));

  vg::StoneSimulation sim(board_scene());
  now = kStart;
  set_up(sim, now);
  const std::vector<vg::StoneStateEntry> before = vg::stone_states(sim);
  place(sim, drop);
  std::string name = "(refused)";
  try {
    name = place(sim, at(point, "black"));
    a.asked = "(accepted)";
  } catch (const vg::InvalidArgument& e) {
    a.asked = e.field();
  }
  std::vector<vg::SegmentEvent> events;
  run(sim, now, 10 * kMs, events);
  const std::vector<vg::StoneStateEntry> after = vg::stone_states(sim);
  a.placed = find(after, name) != nullptr && sim.clear() == "applied at the next physics step";
  for (const vg::StoneStateEntry& b : before) {
    if (const vg::StoneStateEntry* e = find(after, b.name)) {
      a.base_moved_m = std::max(
          a.base_moved_m, (e->output.position_world - b.output.position_world).head<2>().norm());
    }
  }

  vg::World world(*sim.world_config(), std::vector<vg::RigidBodyState>{}, 0.0);
  std::vector<vg::WorldEvent> world_events;
  const auto color_of = [](const std::string& c) {
    return c == "white" ? vg::StoneColor::white : vg::StoneColor::black;
  };
  for (const auto& [p, color] : base) {
    (void)vg::set_down_stone(world, color_of(color), vg::parse_gtp_point(p), 0.0, world_events);
  }
  (void)vg::drop_stone(world, color_of(drop.color), vg::parse_gtp_point(drop.point),
                       drop.drop_height_m, 0.0, world_events);
  a.applied = "(accepted)";
  try {
    (void)vg::set_down_stone(world, vg::StoneColor::black, vg::parse_gtp_point(point), 0.0,
                             world_events);
  } catch (const vg::InvalidArgument& e) {
    a.applied = e.field();
  }
  return a;
}

vg::PlaceRequest dropped(const std::string& point, double height_m) {
  vg::PlaceRequest r = at(point, "black");
  r.drop_height_m = height_m;
  return r;
}

}  // namespace

// A set-down queued behind a drop in the same step is judged on the layout the drop leaves. Two
// blacks set down at C2 lie 11.1 mm either side of it (the second nudged the first), a white on
// A2. Alone, a black set down at A2 fits: the white is pushed 10.9 mm right and the new stone
// lies 11.1 mm left of A2, its centre 3 mm inside the board's left edge. A black dropped onto C2
// first finds no free spot and nudges its neighbours apart: the inner black comes to 21.9 mm
// from A2, touching the white (moved 0.19 mm left), so the set-down at A2 would push a stone off
// the top face (figures measured with drop_stone and set_down_stone). Before a1e9aef the room
// check ignored queued drops: it took the set-down, which the World then refused ("black_4 was
// not placed").
TEST(StoneSimulationNames, ASetDownBehindANudgingDropGetsTheAnswerItsApplicationGets) {
  const SetDownAnswers a = set_down_answers({{"C2", "black"}, {"C2", "black"}, {"A2", "white"}},
                                            dropped("C2", 0.05), "A2");
  EXPECT_EQ(a.alone, "(accepted)");
  EXPECT_GT(a.base_moved_m, 1e-4) << "the drop did not nudge";
  EXPECT_EQ(a.applied, "point") << "the scene lost its point: the nudge leaves room at A2";
  EXPECT_EQ(a.asked, a.applied);
  if (a.asked == "(accepted)") {
    EXPECT_TRUE(a.placed) << "accepted when asked, refused when applied";
  }
}

// A dropped stone is let go at its drop height: a set-down in the same step meets it there, not
// on the board. From 5 cm its ball (radius 11.1 mm) clears a set-down's height band and it is in
// nobody's way; from 5 mm it is. Onto A1 over a black lying there, and onto B1 between blacks on
// A1 and C1 under a white on B2 (a free spot 2.97 mm below B1, no nudge), then a black set down
// at A1: answered as applied at every height.
TEST(StoneSimulationNames, ASetDownBehindADropMeetsItAtItsDropHeight) {
  using Base = std::vector<std::pair<std::string, std::string>>;
  const Base a1{{"A1", "black"}};
  const Base a1_c1_b2{{"A1", "black"}, {"C1", "black"}, {"B2", "white"}};
  for (const double height_m : {0.005, 0.05}) {
    for (const auto& [base, drop_point] : {std::pair{a1, "A1"}, std::pair{a1_c1_b2, "B1"}}) {
      const SetDownAnswers a = set_down_answers(base, dropped(drop_point, height_m), "A1");
      SCOPED_TRACE(std::string("drop onto ") + drop_point + " from " + std::to_string(height_m));
      EXPECT_EQ(a.alone, "(accepted)");
      // From 5 cm the drop changes nothing for the set-down (the scene's point).
      if (height_m == 0.05) {
        EXPECT_EQ(a.applied, "(accepted)");
      }
      EXPECT_EQ(a.asked, a.applied);
      if (a.asked == "(accepted)") {
        EXPECT_TRUE(a.placed) << "accepted when asked, not placed";
      }
    }
  }
}
