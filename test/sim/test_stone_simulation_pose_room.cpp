// A set-down at a Go point meets the stones placed by pose as it meets those placed at points:
// queued in the same physics step, a stone placed by pose flat on the board is in the set-down's
// way, so the room check (StoneSimulation::check_room) answers what the application gets, and
// the stone set down never overlaps it. Geometry from the definitions: A1 lies 3 mm inside
// the board's left edge at (-0.198 m, -0.2133 m) (19 lines at 22 x 23.7 mm on 424.2 x 454.5 mm),
// stones are 22.2 mm (black) wide, so a black lying on A1 leaves no room for a second at A1
// (pushed a full width left or down, it would leave the board) but room at B1 beside it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/sim_test_support.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/sim/stone_simulation.h"
#include "virtual_go/sim/stone_states.h"

namespace vg = virtual_go;
using namespace simtest;

namespace {

constexpr double kBlackHalfWidth = 0.0111, kHalfHeight = 0.0046;  // m, size 33 black
// The grid: A1 and the pitch (m), 19 lines centred on the board.
constexpr double kPitchX = 0.022, kPitchY = 0.0237, kA1X = -9 * kPitchX, kA1Y = -9 * kPitchY;

void run(vg::StoneSimulation& sim, std::int64_t& now, std::int64_t duration_ns) {
  const std::int64_t end = now + duration_ns;
  for (; now <= end; now += 10 * kMs) {
    const vg::UpdateResult r = sim.update(now);
    ASSERT_TRUE(r.error.empty()) << r.error;
  }
}

// A black placed by pose lying flat on the board over the intersection of `point` (its lowest
// point 1 nm above the top face at z = 0).
vg::PlaceRequest by_pose_on(const std::string& point) {
  vg::PlaceRequest r;
  r.color = "black";
  const vg::GoPoint p = vg::parse_gtp_point(point);
  r.position_world =
      Eigen::Vector3d(kA1X + kPitchX * p.column, kA1Y + kPitchY * p.row, kHalfHeight + 1e-9);
  return r;
}

vg::PlaceRequest set_down_at(const std::string& point) {
  vg::PlaceRequest r;
  r.point = point;
  r.color = "black";
  return r;
}

struct Outcome {
  std::string asked;    // "(accepted)" or the refusal's field
  std::string note;     // the answer after the step ("applied at the next physics step" or a note)
  bool placed = false;  // the set-down stone is on the board after the step
  double centre_distance_m = 0.0;  // horizontal, from the pose stone to the set-down one
};

// The pose stone and the set-down asked in one step, then the step; the layout after it.
Outcome pose_then_set_down(const std::string& pose_point, const std::string& set_down_point) {
  vg::StoneSimulation sim(board_scene());
  std::int64_t now = kStart;
  run(sim, now, 10 * kMs);
  std::string answer;
  const std::string pose_name = sim.place(by_pose_on(pose_point), answer);
  Outcome o;
  std::string name;
  try {
    name = sim.place(set_down_at(set_down_point), answer);
    o.asked = "(accepted)";
  } catch (const vg::InvalidArgument& e) {
    o.asked = e.field();
  }
  run(sim, now, 20 * kMs);
  const std::vector<vg::StoneStateEntry> states = vg::stone_states(sim);
  const vg::StoneStateEntry *pose = nullptr, *set = nullptr;
  for (const vg::StoneStateEntry& e : states) {
    if (e.name == pose_name) pose = &e;
    if (!name.empty() && e.name == name) set = &e;
  }
  o.placed = set != nullptr;
  if (pose && set) {
    o.centre_distance_m =
        (set->output.position_world - pose->output.position_world).head<2>().norm();
  }
  o.note = sim.clear();
  return o;
}

}  // namespace

// A black by pose on A1 leaves no room at A1: the set-down is refused when asked ("point"),
// not accepted and then dropped by the World ("... was not placed").
TEST(StoneSimulationPoseRoom, ASetDownOntoAStonePlacedByPoseIsRefusedWhenAsked) {
  const Outcome o = pose_then_set_down("A1", "A1");
  EXPECT_EQ(o.asked, "point");
  EXPECT_EQ(o.note, "applied at the next physics step") << "a placement was dropped later";
}

// Beside it, at B1 (22 mm from A1, closer than a black's 22.2 mm width), there is room: the
// set-down takes the free spot nearest B1 and lies clear of the pose stone, touching at most.
TEST(StoneSimulationPoseRoom, ASetDownBesideAStonePlacedByPoseNeverOverlapsIt) {
  const Outcome o = pose_then_set_down("A1", "B1");
  EXPECT_EQ(o.asked, "(accepted)");
  ASSERT_TRUE(o.placed);
  EXPECT_GE(o.centre_distance_m, 2 * kBlackHalfWidth);
  EXPECT_LT(o.centre_distance_m, 2 * kBlackHalfWidth + 1e-6);  // the spot nearest B1: touching
  EXPECT_EQ(o.note, "applied at the next physics step");
}
