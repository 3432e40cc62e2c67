// The nonsmooth fallback: never an overlap in a state it hands out, never an energy gain from one
// committed sub-step to the next (random edge contacts), a stone tipping off the board's edge
// separates into free flight, one on the top face is handed to the plane model, one on the table
// against the board's side settles without creeping, and the committed motion does not depend
// on the times it is sampled at.
#include <gtest/gtest.h>

#include <random>

#include "virtual_go/common/validation.h"
#include "virtual_go/world/nonsmooth_contact.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

// Energies are sums of terms up to ~1e-3 J here; the test evaluates them with its own formula,
// so "no gain" holds up to their round-off.
constexpr double kEnergyRoundOffJ = 1e-18;

vg::BoardDistance board_distance() {
  return vg::BoardDistance(vg::LensGeometry(stone().shape), vg::BoardGeometry{});
}

vg::NonsmoothContact phase_from(const vg::RigidBodyState& s, double t0, double mu = 0.3) {
  const vg::WorldConfig c = config(0.5, mu);
  return vg::NonsmoothContact(board_distance(), c.motion, c.board_material, c.table_material, s,
                              t0);
}

// A flat stone whose bottom cap rests on the +x top edge line, centre `beyond` outside the edge.
vg::RigidBodyState on_edge(double beyond) {
  return at(Vector3d(kHalfX + beyond, 0.0, std::sqrt(kR * kR - beyond * beyond) - kD));
}

TEST(NonsmoothContact, AStoneTippingOffTheEdgeSeparatesWithoutOverlapOrEnergyGain) {
  const double t0 = 0.5, h = vg::NonsmoothContactOptions{}.step_s;
  vg::NonsmoothContact phase = phase_from(on_edge(0.001), t0);
  double previous_energy = energy(on_edge(0.001)), worst_rise = 0, worst_gap = 1;
  vg::NonsmoothOutcome o;
  long k = 0;
  do {
    ++k;
    o = phase.advance(t0 + k * h);
    worst_rise = std::max(worst_rise, energy(o.state) - previous_energy);
    previous_energy = std::min(previous_energy, energy(o.state));
    worst_gap = std::min(worst_gap, proven_gap(o.state));
    ASSERT_LT(k, 20000);
  } while (o.end == vg::NonsmoothEnd::none);
  EXPECT_EQ(o.end, vg::NonsmoothEnd::separated);
  EXPECT_GT(o.state.position_world.x(), kHalfX + 0.001);  // it tipped outwards
  EXPECT_GT((o.state.orientation * Vector3d::UnitZ()).x(), 0.0) << "its +x side went down";
  EXPECT_LE(worst_rise, kEnergyRoundOffJ);
  EXPECT_GE(worst_gap, -1e-12);
  EXPECT_EQ(phase.counters().largest_energy_excess_j, 0.0);
  std::printf(
      "[ tip     ] separated after %.1f ms (%ld sub-steps, %ld impulses), deepest "
      "free-step overlap %.2e m, worst gap %.1e m\n",
      1e3 * (o.time_s - t0), phase.counters().steps, phase.counters().impulses,
      phase.counters().deepest_overlap_m, worst_gap);
}

TEST(NonsmoothContact, TheCommittedMotionDoesNotDependOnTheSampleTimes) {
  const double t0 = 0.25, h = vg::NonsmoothContactOptions{}.step_s;
  vg::NonsmoothContact on_lattice = phase_from(on_edge(0.0015), t0);
  vg::NonsmoothContact sampled = phase_from(on_edge(0.0015), t0);
  vg::NonsmoothOutcome a, b;
  for (long k = 1; a.end == vg::NonsmoothEnd::none; ++k) a = on_lattice.advance(t0 + k * h);
  double worst_gap = 1, lattice_energy = energy(on_edge(0.0015)), worst_sample_rise = 0;
  for (long k = 1; b.end == vg::NonsmoothEnd::none; ++k) {
    b = sampled.advance(t0 + k * 0.37e-4);
    worst_gap = std::min(worst_gap, proven_gap(b.state));
    // A sample between lattice points never exceeds the energy of the lattice state before it.
    worst_sample_rise = std::max(worst_sample_rise, energy(b.state) - lattice_energy);
    lattice_energy = energy(sampled.lattice_state());
  }
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_TRUE(a.state == b.state);  // bitwise
  EXPECT_GE(worst_gap, -1e-12);
  EXPECT_LE(worst_sample_rise, kEnergyRoundOffJ);
}

TEST(NonsmoothContact, RandomEdgeContactsNeverGainEnergyNorOverlap) {
  std::mt19937 rng(20240610);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_rise = 0, worst_gap = 1;
  int ends[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 40; ++trial) {
    // Tilted, touching the +x top edge with the lens point nearest to it, moving and spinning.
    const Quaterniond q(Eigen::AngleAxisd(0.6 * u(rng), Vector3d(u(rng), u(rng), 0).normalized()));
    vg::RigidBodyState s = at(Vector3d(kHalfX + 0.003 * u(rng), 0.01 * u(rng), 0.01), q,
                              0.1 * Vector3d(u(rng), u(rng), u(rng)));
    s = with_omega(s, 10 * Vector3d(u(rng), u(rng), u(rng)));
    const vg::BoardDistance board = board_distance();
    s.position_world.z() -= board.nearest(s).lens.gap_m;  // lowered onto the edge or face
    const vg::BoardContact c = board.nearest(s);
    s.position_world += -c.lens.gap_m * c.lens.normal_world;
    vg::NonsmoothContact phase = phase_from(s, 0.0, 0.1 + 0.8 * std::abs(u(rng)));
    double previous = energy(s);
    vg::NonsmoothOutcome o;
    for (long k = 1; k <= 3000 && o.end == vg::NonsmoothEnd::none; ++k) {
      o = phase.advance(k * 1e-4);
      worst_rise = std::max(worst_rise, energy(o.state) - previous);
      previous = std::min(previous, energy(o.state));
      worst_gap = std::min(worst_gap, proven_gap(o.state));
    }
    ++ends[static_cast<int>(o.end)];
    EXPECT_EQ(phase.counters().largest_energy_excess_j, 0.0);
  }
  EXPECT_LE(worst_rise, kEnergyRoundOffJ);
  EXPECT_GE(worst_gap, -1e-12);
  std::printf(
      "[ random  ] 40 edge contacts: worst energy rise %.1e J, worst gap %.1e m; ends: "
      "%d running, %d separated, %d plane, %d rest\n",
      worst_rise, worst_gap, ends[0], ends[1], ends[2], ends[3]);
}

TEST(NonsmoothContact, OnTheTopFaceTheExactPlaneModelTakesOver) {
  const double t0 = 1.0, h = vg::NonsmoothContactOptions{}.step_s;
  vg::NonsmoothContact phase = phase_from(at(Vector3d(0.05, 0.02, kC)), t0);
  const vg::NonsmoothOutcome o = phase.advance(t0 + 5 * h);
  EXPECT_EQ(o.end, vg::NonsmoothEnd::plane);
  EXPECT_EQ(o.time_s, t0 + h);
  ASSERT_TRUE(o.plane.has_value());
  EXPECT_EQ(o.plane->feature.kind, vg::BoardFeatureKind::top_face);
  EXPECT_GE(plane_gap(o.state, 0.0), 0.0);
  EXPECT_LE(plane_gap(o.state, 0.0), 1e-12);
  // Only that time may be asked for again.
  EXPECT_NO_THROW(phase.advance(o.time_s));
  EXPECT_THROW(phase.advance(o.time_s + h), vg::InvalidArgument);
}

TEST(NonsmoothContact, AFreeStoneSeparatesAtOnce) {
  vg::NonsmoothContact phase =
      phase_from(at(Vector3d(0, 0, 0.05), Quaterniond::Identity(), Vector3d(0, 0, 1)), 0.0);
  const vg::NonsmoothOutcome o = phase.advance(1.0);
  EXPECT_EQ(o.end, vg::NonsmoothEnd::separated);
  EXPECT_EQ(o.time_s, vg::NonsmoothContactOptions{}.step_s);
  EXPECT_EQ(phase.counters().impulses, 0);
}

TEST(NonsmoothContact, AStoneOnTheTableAgainstTheSideSettlesWithoutCreeping) {
  // Flat on the table, its rim touching the board's +x side: two contacts, the table carrying
  // the weight. It must not move and must come to rest after rest_time_s.
  const vg::RigidBodyState s = at(Vector3d(kHalfX + kA, 0.0, -kThickness + kC));
  vg::NonsmoothContact phase = phase_from(s, 0.0);
  vg::NonsmoothOutcome o;
  double worst_drift = 0;
  for (long k = 1; k <= 1000 && o.end == vg::NonsmoothEnd::none; ++k) {
    o = phase.advance(k * 1e-4);
    worst_drift = std::max(worst_drift, (o.state.position_world - s.position_world).norm());
  }
  EXPECT_EQ(o.end, vg::NonsmoothEnd::rest);
  EXPECT_NEAR(o.time_s, vg::NonsmoothContactOptions{}.rest_time_s, 2e-4);
  EXPECT_EQ(o.state.velocity_world, Vector3d::Zero());
  EXPECT_EQ(o.state.angular_momentum_world, Vector3d::Zero());
  EXPECT_LE(worst_drift, 1e-12);
  EXPECT_GE(proven_gap(o.state), -1e-12);
}

TEST(NonsmoothContact, BadOptionsAreRefusedByName) {
  vg::NonsmoothContactOptions o;
  o.step_s = -1e-4;
  try {
    vg::validate_nonsmooth_options(o);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "nonsmooth/step_s");
  }
  o = vg::NonsmoothContactOptions{};
  o.rest_time_s = std::nan("");
  EXPECT_THROW(vg::validate_nonsmooth_options(o), vg::InvalidArgument);
}

}  // namespace
