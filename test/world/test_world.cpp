// The world against physics: flat drops against their closed form (impact times, apex heights
// e^(2n) h0, bounce counts, time to rest as the bounce series cut at the Zeno height), no energy
// gain and no overlap in any sampled state, Jellett's integral through flight, cap impacts and
// sliding, a tilted spinning toss that comes to exact rest within the rolling resistance's tilt,
// flight samples against the closed form written in the test, a resting stone that costs nothing
// (counters) and stays bitwise still, a full resting board that costs nothing, tengen dropped into
// it with stone contact on (energy, overlap, exact rest) and off (only it visited), a command that
// wakes a stone, determinism, and events that do not depend on the sampling grid.
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "support/flight_reference.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/world/nonsmooth_island.h"
#include "world/many_stones_support.h"
#include "world/static_balance.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;
using vg::WorldEventKind;

constexpr double kDropHeight = 0.05;  // m, bottom of the flat stone above the board
constexpr double kZenoHeight = 1e-6;  // m, the world's default

struct DropCase {
  double restitution;
  int bounces_above_zeno;  // CONTACT facts: 7 at e* 0.5, 24 at 0.8
};

// The closed form of a flat drop (the pole hits first, K_tn = 0: u_n+ = -e u_n- for any friction):
// fall time sqrt(2 h0 / g), then flights of 2 e^n v0 / g; bounce n rises to e^(2n) h0; the
// bouncing stops at the first impact whose rebound would rise less than h_min.
struct DropClosedForm {
  std::vector<double> impact_times;     // all impacts, the last one the sustained one
  std::vector<double> rebound_heights;  // of the bounces (impacts but the last)
  double rest_time = 0.0;
  double uncut_rest_time = 0.0;  // sqrt(2 h0 / g) (1 + e) / (1 - e): the infinite series
};

DropClosedForm drop_closed_form(double e, double h0) {
  DropClosedForm f;
  const double fall = std::sqrt(2 * h0 / kG), v0 = kG * fall;
  double t = fall, v = v0;
  f.impact_times.push_back(t);
  for (;;) {
    const double rebound = e * v;
    if (rebound * rebound / (2 * kG) < kZenoHeight) break;
    f.rebound_heights.push_back(rebound * rebound / (2 * kG));
    t += 2 * rebound / kG;
    v = rebound;
    f.impact_times.push_back(t);
  }
  f.rest_time = t;
  f.uncut_rest_time = fall * (1 + e) / (1 - e);
  return f;
}

TEST(WorldDrop, FlatDropsFollowTheClosedForm) {
  for (const DropCase& c : {DropCase{0.5, 7}, DropCase{0.8, 24}}) {
    SCOPED_TRACE("restitution " + std::to_string(c.restitution));
    const DropClosedForm f = drop_closed_form(c.restitution, kDropHeight);
    ASSERT_EQ(static_cast<int>(f.rebound_heights.size()), c.bounces_above_zeno);
    vg::World world(config(c.restitution), at(Vector3d(0.05, -0.03, kC + kDropHeight)), 0.0);
    const WorldRun r = run(world, f.rest_time + 0.2, 1e-3);

    const auto impacts = of_kind(r.events, WorldEventKind::impact);
    ASSERT_EQ(impacts.size(), f.impact_times.size());
    double worst_time = 0;
    int above = 0;
    for (std::size_t n = 0; n < impacts.size(); ++n) {
      worst_time = std::max(worst_time, std::abs(impacts[n].time_s - f.impact_times[n]));
      EXPECT_EQ(impacts[n].feature.kind, vg::BoardFeatureKind::top_face);
      EXPECT_LE(impacts[n].energy_change_j, 0.0);
      if (impacts[n].rebound_speed_mps * impacts[n].rebound_speed_mps / (2 * kG) > kZenoHeight) {
        ++above;
      }
    }
    EXPECT_LE(worst_time, 1e-12);
    EXPECT_EQ(above, c.bounces_above_zeno);

    // Rest at the sustained impact: the stone lies flat, its pole on the board, still.
    const vg::WorldEvent* rest = last_of(r.events, WorldEventKind::rest);
    ASSERT_NE(rest, nullptr);
    EXPECT_LE(std::abs(rest->time_s - f.rest_time), 1e-12);
    EXPECT_EQ(rest->state.velocity_world, Vector3d::Zero());
    EXPECT_EQ(rest->state.angular_momentum_world, Vector3d::Zero());
    EXPECT_NEAR(rest->state.position_world.z(), kC, 1e-15);
    EXPECT_TRUE(world.is_resting(0));
    std::printf(
        "[ drop    ] e* %.1f: %d bounces above 1 um, impact times within %.1e s, rest at "
        "%.6f ms (series cut at h_min; uncut %.6f ms)\n",
        c.restitution, above, worst_time, 1e3 * rest->time_s, 1e3 * f.uncut_rest_time);

    EXPECT_GE(r.worst_gap, -1e-12);
    EXPECT_LE(r.worst_energy_rise, 1e-15);  // no contact phase: round-off only
    r.expect_no_energy_gain();
    std::printf("[ drop    ] worst gap %.1e m, worst energy rise %.1e J\n", r.worst_gap,
                r.worst_energy_rise);

    // Apex heights: sampled at the closed form's apex times.
    vg::World apex_world(config(c.restitution), at(Vector3d(0.05, -0.03, kC + kDropHeight)), 0.0);
    std::vector<vg::WorldEvent> events;
    double worst_apex = 0;
    for (std::size_t n = 0; n < f.rebound_heights.size(); ++n) {
      const double t_apex = f.impact_times[n] + std::sqrt(2 * f.rebound_heights[n] / kG);
      apex_world.advance_to(t_apex, events);
      const double h = apex_world.state(0).position_world.z() - kC;
      const double expected = std::pow(c.restitution, 2.0 * (n + 1)) * kDropHeight;
      worst_apex = std::max(worst_apex, std::abs(h / expected - 1));
    }
    EXPECT_LE(worst_apex, 1e-9);
    std::printf("[ drop    ] apex heights e^(2n) h0 within %.1e relative\n", worst_apex);
  }
}

TEST(WorldDrop, ImpactEnergyLossIsTheRestitutionLaw) {
  // Flat on the pole: dE = -(1 - e*^2) m u_n^2 / 2 for every impact but the sustained one.
  const double e = 0.5;
  vg::World world(config(e), at(Vector3d(0, 0, kC + kDropHeight)), 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(0.5, events);
  const auto impacts = of_kind(events, WorldEventKind::impact);
  ASSERT_GE(impacts.size(), 2u);
  for (std::size_t n = 0; n + 1 < impacts.size(); ++n) {
    const double u = impacts[n].approach_speed_mps;
    EXPECT_NEAR(impacts[n].energy_change_j, -(1 - e * e) * mass() * u * u / 2,
                1e-12 * mass() * u * u);
    EXPECT_NEAR(impacts[n].rebound_speed_mps, e * u, 1e-12 * u);
  }
  // The sustained one removes the approach energy entirely (e* = 0 applied).
  const double u = impacts.back().approach_speed_mps;
  EXPECT_NEAR(impacts.back().energy_change_j, -mass() * u * u / 2, 1e-12 * mass() * u * u);
}

// A stone tilted about a horizontal axis, spinning about its own axis (plus `wobble` times a
// transverse rate), and moving sideways.
vg::RigidBodyState tilted_toss(double tilt, double spin, double speed, double height,
                               double wobble = 1.0) {
  const Quaterniond q(Eigen::AngleAxisd(tilt, Vector3d(0.2, 1, 0).normalized()));
  vg::RigidBodyState s = at(Vector3d(0, 0, height), q, Vector3d(speed, 0.05, 0));
  return with_omega(s, q * Vector3d(0, 0, spin) + wobble * Vector3d(1, -2, 0));
}

TEST(WorldToss, ATiltedSpinningTossLandsSlidesRocksAndComesToExactRest) {
  const vg::RigidBodyState start = tilted_toss(0.3, 10.0, 0.2, 0.03);
  vg::World world(config(0.5, 0.3, 5e-6, 15e-6), start, 0.0);
  WorldRun r;
  for (double t = 1.0; t <= 60.0 && !world.is_resting(0); t += 1.0) run_into(r, world, t, 1e-3);
  ASSERT_TRUE(world.is_resting(0));
  EXPECT_GE(of_kind(r.events, WorldEventKind::impact).size(), 2u);
  EXPECT_GE(of_kind(r.events, WorldEventKind::slide).size(), 1u);
  EXPECT_GE(of_kind(r.events, WorldEventKind::roll).size(), 1u);
  const vg::WorldEvent* rest = last_of(r.events, WorldEventKind::rest);
  ASSERT_NE(rest, nullptr);
  EXPECT_EQ(rest->detail, vg::WorldEventDetail::rest);  // the exact plane model's rest
  // Exact rest: velocities exactly zero, on the board, tilted no more than the rolling
  // resistance can hold: m g d sin(theta) <= l_r N with N = m g.
  const vg::RigidBodyState& s = world.state(0);
  EXPECT_EQ(s.velocity_world, Vector3d::Zero());
  EXPECT_EQ(s.angular_momentum_world, Vector3d::Zero());
  EXPECT_NEAR(plane_gap(s, 0.0), 0.0, 1e-15);
  const double tilt = std::acos(std::min(1.0, std::abs((s.orientation * Vector3d::UnitZ()).z())));
  EXPECT_LE(std::sin(tilt), 5e-6 / kD * (1 + 1e-9));
  // Frozen from there on.
  std::vector<vg::WorldEvent> later;
  const vg::RigidBodyState frozen = s;
  world.advance_to(world.time() + 5.0, later);
  EXPECT_TRUE(later.empty());
  EXPECT_TRUE(world.state(0) == frozen);
  EXPECT_GE(r.worst_gap, -1e-12);
  r.expect_no_energy_gain();
  const vg::WorldCounters& c = world.counters();
  std::printf(
      "[ toss    ] rest at %.3f s after %zu events, tilt %.2e rad (l_r/d %.2e), worst gap "
      "%.1e m, energy above start %.1e J, worst rise over an earlier state %.1e J; %ld "
      "flight steps, %ld searches, %ld impacts, %ld contact steps\n",
      rest->time_s, r.events.size(), tilt, 5e-6 / kD, r.worst_gap, r.worst_energy_above_start,
      r.worst_energy_rise, c.flight_steps, c.contact_searches, c.impacts, c.plane_contact_steps);
}

TEST(WorldToss, TwoIdenticalRunsAreBitwiseIdentical) {
  auto once = [] {
    vg::World world(config(0.5, 0.3), tilted_toss(0.3, 10.0, 0.2, 0.03), 0.0);
    const WorldRun r = run(world, 2.0, 1e-3);
    return std::make_pair(r.events, world.state(0));
  };
  const auto a = once(), b = once();
  ASSERT_EQ(a.first.size(), b.first.size());
  for (std::size_t i = 0; i < a.first.size(); ++i) {
    EXPECT_EQ(a.first[i].time_s, b.first[i].time_s);
    EXPECT_EQ(a.first[i].kind, b.first[i].kind);
    EXPECT_EQ(a.first[i].detail, b.first[i].detail);
    EXPECT_TRUE(a.first[i].state == b.first[i].state);
  }
  EXPECT_TRUE(a.second == b.second);
}

TEST(WorldToss, AGridAndOneCallGiveTheSameEvents) {
  const vg::RigidBodyState start = tilted_toss(0.3, 10.0, 0.2, 0.03);
  vg::World gridded(config(0.5, 0.3), start, 0.0);
  const WorldRun r = run(gridded, 2.0, 1e-3);
  vg::World once(config(0.5, 0.3), start, 0.0);
  std::vector<vg::WorldEvent> events;
  once.advance_to(2.0, events);
  ASSERT_EQ(events.size(), r.events.size());
  double worst = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].detail, r.events[i].detail);
    worst = std::max(worst, std::abs(events[i].time_s - r.events[i].time_s));
  }
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE((once.state(0).position_world - gridded.state(0).position_world).norm(), 1e-12);
  std::printf("[ grid    ] %zu events over 2 s: 1 ms grid vs one call within %.1e s\n",
              events.size(), worst);
}

TEST(WorldToss, JellettsIntegralThroughFlightCapImpactsAndSliding) {
  // Without rolling resistance and spinning friction, J = L . (x_G - P) = L . (R e_z - d b) is
  // conserved through flight (L constant, b precessing about L), cap impacts on the horizontal
  // plane and sliding or rolling on it (docs/physics.md, "Sustained contact").
  vg::World world(config(0.5, 0.3, 0.0, 0.0), tilted_toss(0.2, 12.0, 0.2, 0.02, 0.0), 0.0);
  const double j0 = jellett(world.state(0));
  const WorldRun r = run(world, 1.0, 1e-3);
  double worst = 0;
  bool slid = false;
  for (const auto& e : r.events) {
    // Every contact on the bottom cap (in flight the tilt does not matter: L is constant and b
    // precesses about it).
    ASSERT_NE(e.kind, WorldEventKind::rim) << "the case must stay on the bottom cap";
    if (e.has_feature) EXPECT_EQ(e.part, vg::LensPart::bottom_cap);
    worst = std::max(worst, std::abs(jellett(e.state) - j0));
    slid = slid || e.kind == WorldEventKind::slide;
  }
  for (const auto& s : r.states) worst = std::max(worst, std::abs(jellett(s) - j0));
  EXPECT_TRUE(slid);
  EXPECT_GE(of_kind(r.events, WorldEventKind::impact).size(), 2u);
  EXPECT_LE(worst, 1e-9 * std::abs(j0));
  std::printf(
      "[ jellett ] J = %.6e kg m^3/s held to %.1e relative over %zu events and 1000 samples\n", j0,
      worst / std::abs(j0), r.events.size());
  EXPECT_GE(r.worst_gap, -1e-12);
}

TEST(WorldFlight, FlightSamplesAreTheClosedFormFromTheLastEvent) {
  // A tumbling throw from 30 cm: every 1 ms sample of a flight equals the closed form (parabola
  // and torque-free axisymmetric top, written in the test) started at the flight's first state,
  // which is the last event's (or the initial state).
  const Quaterniond q0(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 0.5).normalized()));
  vg::RigidBodyState s = at(Vector3d(0.02, -0.01, 0.3), q0, Vector3d(0.3, -0.2, 0.5));
  s = with_omega(s, Vector3d(20, -35, 15));
  vg::World world(config(0.5), s, 0.0);
  const auto mp = stone().mass_properties;
  vgtest::FlightReference flight{kA, kC, s.position_world, s.velocity_world, kGravity, {}};
  flight.top =
      vgtest::AxisymmetricTop{mp.principal_moments_body().x(), mp.principal_moments_body().z(),
                              vgtest::from_eigen(s.orientation), s.angular_momentum_world};
  double anchor_time = 0.0;
  double worst_position = 0, worst_angle = 0, worst_velocity = 0;
  long compared = 0;
  std::vector<vg::WorldEvent> events;
  for (int k = 1; k <= 2000; ++k) {
    const double t = k * 1e-3;
    const std::size_t before = events.size();
    world.advance_to(t, events);
    if (events.size() != before) {
      const vg::RigidBodyState& e = events.back().state;
      anchor_time = events.back().time_s;
      flight.x0 = e.position_world;
      flight.v0 = e.velocity_world;
      flight.top.q0 = vgtest::from_eigen(e.orientation);
      flight.top.l_world = e.angular_momentum_world;
    }
    if (world.mode(0) != vg::StoneMode::flight) continue;
    const vg::RigidBodyState& w = world.state(0);
    const double tau = t - anchor_time;
    worst_position = std::max(worst_position, (w.position_world - flight.position_at(tau)).norm());
    worst_velocity =
        std::max(worst_velocity, (w.velocity_world - (flight.v0 + kGravity * tau)).norm());
    worst_angle = std::max(worst_angle, vgtest::angle_between(vgtest::from_eigen(w.orientation),
                                                              flight.orientation_at(tau)));
    ++compared;
  }
  EXPECT_GE(of_kind(events, WorldEventKind::impact).size(), 1u);
  EXPECT_GT(compared, 300);
  EXPECT_LE(worst_position, 1e-12);
  EXPECT_LE(worst_velocity, 1e-12);
  EXPECT_LE(worst_angle, 1e-12);
  std::printf(
      "[ flight  ] %ld flight samples vs closed form: position %.1e m, velocity %.1e m/s, "
      "orientation %.1e rad\n",
      compared, worst_position, worst_velocity, worst_angle);
}

TEST(WorldFlight, OneContactSearchPerFlight) {
  // A drop from 1 m without hitting anything for 0.45 s: one search at the start, none while
  // the flight is sampled on its grid.
  vg::World world(config(0.5), at(Vector3d(0, 0, 1.0)), 0.0);
  EXPECT_EQ(world.counters().contact_searches, 1);
  const double t_hit = std::sqrt(2 * (1.0 - kC) / kG);
  EXPECT_NEAR(world.next_contact_time(0), t_hit, 1e-12);
  std::vector<vg::WorldEvent> events;
  for (int k = 1; k <= 400; ++k) world.advance_to(k * 1e-3, events);
  EXPECT_EQ(world.counters().contact_searches, 1);
  EXPECT_EQ(world.counters().flight_steps, 400);
  EXPECT_TRUE(events.empty());
}

TEST(WorldRest, ARestingStoneCostsNothingAndStaysBitwiseStill) {
  vg::World world(config(0.5), at(Vector3d(0.1, 0.05, kC + 0.01)), 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(0.3, events);
  ASSERT_TRUE(world.is_resting(0));
  const vg::RigidBodyState frozen = world.state(0);
  const vg::WorldCounters before = world.counters();
  const std::size_t events_before = events.size();
  for (long k = 1; k <= 1000000; ++k) world.advance_to(0.3 + k * 1e-3, events);
  const vg::WorldCounters& after = world.counters();
  EXPECT_TRUE(world.state(0) == frozen);  // bitwise
  EXPECT_EQ(after.advance_calls - before.advance_calls, 1000000);
  EXPECT_EQ(after.flight_steps, before.flight_steps);
  EXPECT_EQ(after.contact_searches, before.contact_searches);
  EXPECT_EQ(after.plane_contact_steps, before.plane_contact_steps);
  EXPECT_EQ(after.plane_contact_rhs, before.plane_contact_rhs);
  EXPECT_EQ(after.nonsmooth_steps, before.nonsmooth_steps);
  EXPECT_EQ(after.impacts, before.impacts);
  EXPECT_EQ(events.size(), events_before);
  EXPECT_TRUE(world.is_resting(0));
  // At rest: the pole on the board, velocities exactly zero.
  EXPECT_EQ(frozen.velocity_world, Vector3d::Zero());
  EXPECT_EQ(frozen.angular_momentum_world, Vector3d::Zero());
  EXPECT_NEAR(plane_gap(frozen, 0.0), 0.0, 1e-15);
}

// Every counter but advance_calls, for "no work was done".
void expect_same_work(const vg::WorldCounters& a, const vg::WorldCounters& b) {
  EXPECT_EQ(a.flight_steps, b.flight_steps);
  EXPECT_EQ(a.contact_searches, b.contact_searches);
  EXPECT_EQ(a.contact_search_steps, b.contact_search_steps);
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_EQ(a.impact_slip_steps, b.impact_slip_steps);
  EXPECT_EQ(a.plane_contact_steps, b.plane_contact_steps);
  EXPECT_EQ(a.plane_contact_rhs, b.plane_contact_rhs);
  EXPECT_EQ(a.nonsmooth_steps, b.nonsmooth_steps);
  EXPECT_EQ(a.nonsmooth_impulses, b.nonsmooth_impulses);
  EXPECT_EQ(a.events, b.events);
  EXPECT_EQ(a.stones_visited, b.stones_visited);
  EXPECT_EQ(a.pair_searches, b.pair_searches);
  EXPECT_EQ(a.pair_search_steps, b.pair_search_steps);
  EXPECT_EQ(a.pair_gap_checks, b.pair_gap_checks);
  EXPECT_EQ(a.broad_phase_tests, b.broad_phase_tests);
  EXPECT_EQ(a.pair_candidates, b.pair_candidates);
  EXPECT_EQ(a.islands_formed, b.islands_formed);
}

// 361 stones set down flat on every point (pole on the top face: z_G = c, at rest at once): 22 mm
// lenses on the 22 mm x 23.7 mm grid, so each row is a line of stones whose rims touch.
struct FullBoard {
  vg::WorldConfig config;
  std::vector<vg::RigidBodyState> set_down;
  std::size_t tengen = vg::point_index(vg::parse_gtp_point("K10"));

  explicit FullBoard(bool stone_contact) : config(worldtest::config(0.5)) {
    config.stone_contact = stone_contact;
    for (int index = 0; index < vg::kGoLines * vg::kGoLines; ++index) {
      const Vector3d p = vg::go_point_world(config.board, vg::point_at_index(index));
      set_down.push_back(at(Vector3d(p.x(), p.y(), p.z() + kC)));
    }
  }
};

// Issue 15: a resting full board costs what an empty one does (stone contact on, the default).
// After the first call 10^6 calls visit no stone (stones_visited stays put) and do no work, pair
// work included; states bitwise frozen. A reset wakes them all again.
TEST(WorldRest, AFullRestingBoardIsNeverVisited) {
  const FullBoard b(true);
  ASSERT_TRUE(vg::WorldConfig(b.config.motion, b.config.shape).stone_contact);  // the default
  const std::vector<vg::RigidBodyState>& stones = b.set_down;
  vg::World world(b.config, stones, 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(1e-3, events);
  ASSERT_TRUE(world.all_resting());
  ASSERT_EQ(of_kind(events, WorldEventKind::rest).size(), stones.size());
  std::vector<vg::RigidBodyState> frozen;
  for (std::size_t i = 0; i < stones.size(); ++i) {
    frozen.push_back(world.state(i));
    // Where it was set down (flat on its point), velocities exactly zero.
    EXPECT_NEAR((frozen[i].position_world - stones[i].position_world).norm(), 0.0, 1e-15);
    EXPECT_EQ(frozen[i].velocity_world, Vector3d::Zero());
    EXPECT_EQ(frozen[i].angular_momentum_world, Vector3d::Zero());
  }
  const vg::WorldCounters before = world.counters();
  EXPECT_EQ(before.stones_visited, static_cast<long>(stones.size()));  // the first call only
  const std::size_t events_before = events.size();
  for (long k = 1; k <= 1000000; ++k) world.advance_to(1e-3 + k * 1e-3, events);
  EXPECT_EQ(world.counters().advance_calls - before.advance_calls, 1000000);
  expect_same_work(world.counters(), before);
  EXPECT_EQ(events.size(), events_before);
  for (std::size_t i = 0; i < stones.size(); ++i) {
    EXPECT_TRUE(world.state(i) == frozen[i]) << "stone " << i;  // bitwise
    EXPECT_TRUE(world.is_resting(i));
  }

  // A reset wakes them all again.
  world.reset(stones, 0.0);
  EXPECT_FALSE(world.all_resting());
  world.advance_to(1e-3, events);
  EXPECT_EQ(world.counters().stones_visited, static_cast<long>(stones.size()));
  EXPECT_TRUE(world.all_resting());
}

// Stone contact on (the default): tengen lifted 1 cm above the full board falls into its slot,
// whose width is exactly its own, and lands on its row neighbours' rims as it meets the board (a
// three-body impact); the knocked neighbours move and everything settles. Checked at every call
// (1 ms grid) against physics written here: the total energy never rises (from the inertia
// tensor, over the stones that moved; the others' is constant); no two lenses overlap by more
// than 1e-9 m (a proven lower bound, for every pair with a stone that moved; the pairs of
// unmoved stones are those of the set-down board, checked once) and no lens dips into the board;
// a stone no event names stays bitwise where it was set down; everything comes to exact rest
// (velocities exactly zero), and the board at rest then costs nothing (counters unchanged over
// 10^5 calls, states bitwise frozen).
TEST(WorldRest, TengenDroppedIntoAFullBoardKnocksItsNeighboursAndAllRest) {
  const FullBoard b(true);
  vg::World world(b.config, b.set_down, 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(1e-3, events);
  ASSERT_TRUE(world.all_resting());
  const std::size_t n = b.set_down.size();
  std::vector<vg::RigidBodyState> frozen;
  for (std::size_t i = 0; i < n; ++i) frozen.push_back(world.state(i));
  // The set-down board: rims touch along the rows, nothing overlaps.
  double set_down_gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((frozen[i].position_world - frozen[j].position_world).norm() > 2 * kA + 1e-6) continue;
      set_down_gap =
          std::min(set_down_gap, pair_gap_bound(lens_ref(frozen[i]), lens_ref(frozen[j])));
    }
  }
  EXPECT_GE(set_down_gap, -1e-9);

  const std::size_t tengen = b.tengen;
  vg::RigidBodyState lifted = world.state(tengen);
  lifted.position_world.z() += 0.01;
  double t = world.time();
  const std::size_t first_event = events.size();
  world.set_state(tengen, lifted, t, events);
  ASSERT_FALSE(world.all_resting());
  const double e_in = mass() * kG * 0.01;  // the energy the lift brought in
  // Energies relative to the set-down board: only stones that moved contribute.
  const auto energy_above_set_down = [&] {
    double e = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!(world.state(i) == frozen[i])) e += energy(world.state(i)) - energy(frozen[i]);
    }
    return e;
  };
  double lowest = energy_above_set_down(), worst_rise = 0.0;
  double worst_gap = std::numeric_limits<double>::infinity(), worst_board = worst_gap;
  double largest_shift = 0.0, largest_turn = 0.0;
  const vg::WorldCounters start = world.counters();
  long calls = 0, most_passes = 0;
  std::vector<vg::RigidBodyState> previous = frozen;
  std::vector<bool> changed(n, false);
  while (!world.all_resting() && calls < 10000) {
    const long passes_before = world.counters().stages;
    world.advance_to(t += 1e-3, events);
    ++calls;
    most_passes = std::max(most_passes, world.counters().stages - passes_before);
    const double e = energy_above_set_down();
    worst_rise = std::max(worst_rise, (e - lowest) / e_in);
    lowest = std::min(lowest, e);
    // Pairs and board gaps where a stone changed in this call (the others are as last checked).
    for (std::size_t i = 0; i < n; ++i) changed[i] = !(world.state(i) == previous[i]);
    for (std::size_t i = 0; i < n; ++i) {
      if (!changed[i]) continue;
      const vg::RigidBodyState& s = world.state(i);
      worst_board = std::min(worst_board, plane_gap(s, 0.0));
      if (i != tengen) {
        largest_shift =
            std::max(largest_shift, (s.position_world - frozen[i].position_world).norm());
        largest_turn = std::max(largest_turn, s.orientation.angularDistance(frozen[i].orientation));
      }
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || (j < i && changed[j])) continue;  // each pair once
        if ((world.state(j).position_world - s.position_world).norm() > 2 * kA + 1e-6) continue;
        worst_gap = std::min(worst_gap, pair_gap_bound(lens_ref(s), lens_ref(world.state(j))));
      }
      previous[i] = s;
    }
  }
  ASSERT_TRUE(world.all_resting()) << "not at rest after " << calls << " ms";
  const vg::WorldCounters settled = world.counters();
  EXPECT_LE(worst_rise, 1e-11);
  EXPECT_GE(worst_gap, -1e-9);
  EXPECT_GE(worst_board, -1e-9);
  // Its neighbours were knocked: more than tengen moved (with contact off only tengen would).
  EXPECT_GT(settled.stones_visited - start.stones_visited, calls);
  EXPECT_GT(largest_shift, 0.0);
  // Exact rest: velocities exactly zero everywhere; stones no event named never moved.
  std::vector<bool> named(n, false);
  for (std::size_t e = first_event; e < events.size(); ++e) {
    named[world.index_of(events[e].id)] = true;
    if (events[e].other) named[world.index_of(*events[e].other)] = true;
  }
  int moved = 0;
  std::vector<vg::RigidBodyState> rested;
  for (std::size_t i = 0; i < n; ++i) {
    rested.push_back(world.state(i));
    EXPECT_EQ(rested[i].velocity_world, Vector3d::Zero()) << "stone " << i;
    EXPECT_EQ(rested[i].angular_momentum_world, Vector3d::Zero()) << "stone " << i;
    if (!named[i]) EXPECT_TRUE(rested[i] == frozen[i]) << "stone " << i;
    moved += !(rested[i] == frozen[i]);
  }
  // The stones that moved rest held by their contacts (static_balance.h: forces and couples
  // inside the contact laws, the others fixed supports; measured 2e-16 of m g).
  std::vector<bool> moved_now(n, false);
  for (std::size_t i = 0; i < n; ++i) moved_now[i] = !(rested[i] == frozen[i]);
  EXPECT_EQ(print_unheld("tengen and the stones it moved", world, kGravity, 1e-9, moved_now), 0);
  // The board at rest costs nothing again.
  const std::size_t events_settled = events.size();
  for (long k = 1; k <= 100000; ++k) world.advance_to(t + k * 1e-3, events);
  expect_same_work(world.counters(), settled);
  EXPECT_EQ(events.size(), events_settled);
  for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(world.state(i) == rested[i]) << "stone " << i;
  std::printf(
      "[ measured ] tengen dropped 1 cm into the full board: all rest after %ld calls (1 ms); "
      "%d stones moved, neighbours by up to %.3g mm and %.3g rad; %ld stone visits, %ld pair "
      "impacts, %ld islands, %ld island sub-steps, %ld passes (at most %ld in one call); largest "
      "energy rise %.3g of the energy brought in, energy lost %.4f of it; smallest gaps %.3g m "
      "(pairs), %.3g m (board); tengen at rest %.3g mm above the top face (centre minus c), "
      "tilted %.3g rad\n",
      calls, moved, largest_shift * 1e3, largest_turn,
      settled.stones_visited - start.stones_visited, settled.pair_impacts - start.pair_impacts,
      settled.islands_formed - start.islands_formed,
      settled.nonsmooth_steps - start.nonsmooth_steps, settled.stages - start.stages, most_passes,
      worst_rise, (e_in - lowest) / e_in, worst_gap, worst_board,
      (rested[tengen].position_world.z() - kC) * 1e3,
      rested[tengen].orientation.angularDistance(Quaterniond::Identity()));
}

// Stone contact off (the world before issue 15, WorldConfig::stone_contact false): stones pass
// through each other and each moves alone, so lifting tengen above the full board visits it
// and nothing else while it falls, bounces and settles; the other 360 stay bitwise frozen and
// the board at rest costs nothing again.
TEST(WorldRest, WithoutStoneContactALiftedStoneIsTheOnlyOneVisited) {
  const FullBoard b(false);
  vg::World world(b.config, b.set_down, 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(1e-3, events);
  ASSERT_TRUE(world.all_resting());
  std::vector<vg::RigidBodyState> frozen;
  for (std::size_t i = 0; i < b.set_down.size(); ++i) frozen.push_back(world.state(i));
  const std::size_t tengen = b.tengen;
  vg::RigidBodyState lifted = world.state(tengen);
  lifted.position_world.z() += 0.01;
  double t = world.time();
  world.set_state(tengen, lifted, t, events);
  EXPECT_FALSE(world.all_resting());
  long calls = 0;
  const long visited_before = world.counters().stones_visited;
  while (!world.all_resting() && calls < 2000) {
    t += 1e-3;
    world.advance_to(t, events);
    ++calls;
  }
  ASSERT_TRUE(world.all_resting());
  EXPECT_EQ(world.counters().stones_visited - visited_before, calls);
  EXPECT_EQ(world.counters().pair_searches, 0);
  const vg::WorldCounters settled = world.counters();
  for (int k = 0; k < 1000; ++k) world.advance_to(t += 1e-3, events);
  expect_same_work(world.counters(), settled);
  for (std::size_t i = 0; i < b.set_down.size(); ++i) {
    if (i != tengen) EXPECT_TRUE(world.state(i) == frozen[i]) << "stone " << i;
  }
}

// With stone-stone contact on, a resting board is not even handed to the broad phase
// (10^6 calls, every work counter unchanged, pair work included). Then one stone is lifted and
// falls: its passes look only at its neighbours in the board's grid, so they cost exactly what
// they cost with only its eight neighbours on the board (the same broad-phase tests, candidate
// pairs and pair searches, the same state bit for bit).
TEST(WorldRest, AFullRestingBoardWithStoneContactDoesNoPairWork) {
  vg::WorldConfig c = config(0.5);
  c.stone_contact = true;
  const std::size_t tengen = vg::point_index(vg::parse_gtp_point("K10"));
  const Vector3d centre = vg::go_point_world(c.board, vg::point_at_index(static_cast<int>(tengen)));
  std::vector<vg::RigidBodyState> board, block;
  std::size_t tengen_in_block = 0;
  for (int index = 0; index < vg::kGoLines * vg::kGoLines; ++index) {
    const Vector3d p = vg::go_point_world(c.board, vg::point_at_index(index));
    board.push_back(at(Vector3d(p.x(), p.y(), p.z() + kC)));
    // Tengen and its eight neighbours (within one spacing along each axis).
    if (std::abs(p.x() - centre.x()) < 0.03 && std::abs(p.y() - centre.y()) < 0.03) {
      if (static_cast<std::size_t>(index) == tengen) tengen_in_block = block.size();
      block.push_back(board.back());
    }
  }
  ASSERT_EQ(block.size(), 9u);
  vg::World full(c, board, 0.0), few(c, block, 0.0);
  std::vector<vg::WorldEvent> events;
  full.advance_to(1e-3, events);
  few.advance_to(1e-3, events);
  ASSERT_TRUE(full.all_resting());
  ASSERT_TRUE(few.all_resting());
  const vg::WorldCounters before = full.counters();
  for (long k = 1; k <= 1000000; ++k) full.advance_to(1e-3 + k * 1e-3, events);
  expect_same_work(full.counters(), before);  // pair work and broad-phase tests included

  // Lift tengen by 1 cm in both; 30 ms of its fall (it lands after 45 ms).
  const auto lift = [&](vg::World& w, std::size_t i) {
    vg::RigidBodyState s = w.state(i);
    s.position_world.z() += 0.01;
    w.set_state(i, s, w.time(), events);
  };
  few.advance_to(full.time(), events);
  lift(full, tengen);
  lift(few, tengen_in_block);
  const vg::WorldCounters full0 = full.counters(), few0 = few.counters();
  for (int k = 1; k <= 30; ++k) {
    full.advance_to(full.time() + 1e-3, events);
    few.advance_to(full.time(), events);
  }
  EXPECT_TRUE(full.state(tengen) == few.state(tengen_in_block));
  const auto delta = [](const vg::WorldCounters& a, const vg::WorldCounters& b) {
    return std::vector<long>{
        a.broad_phase_tests - b.broad_phase_tests, a.pair_candidates - b.pair_candidates,
        a.pair_searches - b.pair_searches, a.pair_search_steps - b.pair_search_steps,
        a.stones_visited - b.stones_visited};
  };
  EXPECT_EQ(delta(full.counters(), full0), delta(few.counters(), few0));
  EXPECT_EQ(full.counters().stones_visited - full0.stones_visited, 30);   // tengen alone
  EXPECT_GT(full.counters().pair_candidates - full0.pair_candidates, 0);  // it has neighbours
  std::printf(
      "one stone falling among 360 resting, 30 calls: %ld bound tests, %ld candidate "
      "pairs, %ld pair searches\n",
      full.counters().broad_phase_tests - full0.broad_phase_tests,
      full.counters().pair_candidates - full0.pair_candidates,
      full.counters().pair_searches - full0.pair_searches);
}

TEST(WorldRest, ACommandWakesARestingStone) {
  vg::World world(config(0.5), at(Vector3d(0, 0, kC + 0.01)), 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(0.5, events);
  ASSERT_TRUE(world.is_resting(0));
  events.clear();
  // Lifted 2 cm at t = 0.6 s: a wake event carrying the new state, then a fall in closed form.
  vg::RigidBodyState lifted = world.state(0);
  lifted.position_world.z() += 0.02;
  world.set_state(0, lifted, 0.6, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, WorldEventKind::wake);
  EXPECT_EQ(events[0].time_s, 0.6);
  EXPECT_TRUE(events[0].state == lifted.validated());
  EXPECT_EQ(world.mode(0), vg::StoneMode::flight);
  world.advance_to(0.7, events);
  const auto impacts = of_kind(events, WorldEventKind::impact);
  ASSERT_GE(impacts.size(), 1u);
  EXPECT_NEAR(impacts[0].time_s, 0.6 + std::sqrt(2 * 0.02 / kG), 1e-12);
  // A command on a stone that is not resting (still bouncing) wakes nothing.
  ASSERT_EQ(world.mode(0), vg::StoneMode::flight);
  events.clear();
  vg::RigidBodyState higher = world.state(0);
  higher.position_world.z() = 0.1;
  higher.velocity_world.setZero();
  world.set_state(0, higher, 0.7, events);
  EXPECT_TRUE(events.empty());
}

TEST(WorldRest, BadCommandsAreRefusedByNameAndChangeNothing) {
  vg::World world(config(0.5), at(Vector3d(0, 0, 0.1)), 0.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(0.05, events);
  const vg::RigidBodyState before = world.state(0);
  const vg::WorldCounters counters = world.counters();
  auto field_of = [&](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const vg::InvalidArgument& e) {
      return e.field();
    }
    return "";
  };
  // Sunk 1 mm into the board.
  EXPECT_EQ(field_of([&] { world.set_state(0, at(Vector3d(0, 0, kC - 1e-3)), 0.1, events); }),
            "state");
  vg::RigidBodyState nan = before;
  nan.velocity_world.x() = std::nan("");
  EXPECT_EQ(field_of([&] { world.set_state(0, nan, 0.1, events); }), "state");
  EXPECT_EQ(field_of([&] { world.set_state(3, before, 0.1, events); }), "stone");
  EXPECT_EQ(field_of([&] { world.set_state(0, before, 0.01, events); }), "time");
  EXPECT_EQ(field_of([&] { world.advance_to(0.01, events); }), "time");
  EXPECT_EQ(field_of([&] { world.advance_to(std::nan(""), events); }), "time");
  EXPECT_TRUE(world.state(0) == before);
  EXPECT_EQ(world.time(), 0.05);
  EXPECT_EQ(world.counters().flight_steps, counters.flight_steps);
  EXPECT_TRUE(events.empty());
  // Bad configurations name the parameter.
  vg::WorldConfig bad = config();
  bad.board_material.friction = -0.1;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "contact/board/friction");
  bad = config();
  bad.table_material.restitution = 1.5;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "contact/table/restitution");
  bad = config();
  bad.zeno_height_m = 0.0;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "contact/zeno_height");
  bad = config();
  bad.board.size_x_m = -1.0;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "board/size");
  bad = config();
  bad.options.nonsmooth.step_s = 0.0;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "nonsmooth/step_s");
  // Coarser than the verified island sub-step: refused, naming the limit.
  bad.options.nonsmooth.step_s = 2.0 * vg::kNonsmoothLargestStepS;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "nonsmooth/step_s");
  try {
    vg::World w(bad, before, 0.0);
  } catch (const vg::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("at most 0.00025 s"), std::string::npos) << e.what();
  }
  bad.options.nonsmooth.step_s = vg::kNonsmoothLargestStepS;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "");
  // The keep margin's narrowing (the World sets it for its islands; here it is refused).
  bad.options.nonsmooth.keep_s_per_mps = -1.0;
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "nonsmooth/keep_s_per_mps");
  bad.options.nonsmooth.keep_s_per_mps = 0.0;
  bad.options.nonsmooth.keep_join_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(field_of([&] { vg::World w(bad, before, 0.0); }), "nonsmooth/keep_join_m");
}

TEST(WorldBoard, WithoutTheBoardTheStoneFliesForeverAtNoSearchCost) {
  vg::WorldConfig c = config();
  c.board_enabled = false;
  vg::World world(c, at(Vector3d(0, 0, 0.01)), 0.0);
  std::vector<vg::WorldEvent> events;
  for (int k = 1; k <= 1000; ++k) world.advance_to(k * 1e-3, events);
  EXPECT_TRUE(events.empty());
  EXPECT_EQ(world.counters().contact_searches, 0);
  EXPECT_NEAR(world.state(0).position_world.z(), 0.01 - 0.5 * kG, 1e-12);
}

// A state touching the board's top face with the contact point's normal velocity zero.
vg::RigidBodyState touching_top(const Quaterniond& q, const Vector3d& omega) {
  vg::RigidBodyState s = at(Vector3d::Zero(), q);
  const vgtest::LensReference lens = lens_ref(s);
  const Vector3d r = lens.support(-Vector3d::UnitZ()) - lens.x;  // lowest point from G
  s.position_world = Vector3d(0.01, 0.02, -r.z());
  s.velocity_world = Vector3d(0, 0, -omega.cross(r).z());
  return with_omega(s, omega);
}

TEST(WorldLiftOff, AStoneLeavingItsRimFliesOnWithoutTouchingThePlaneItLeft) {
  // Frictionless, on the rim at 50 deg tipping up at 33 rad/s: G moves only vertically,
  // z = a sin(alpha), E = 1/2 (I1 + m a^2 cos^2 alpha) alpha'^2 + m g a sin(alpha), and the
  // normal force vanishes where a sin(alpha) alpha'^2 = g. The world must then fly the stone
  // in closed form: its gap opens at third order, and the search must not report the plane it
  // just left.
  const double i1 = stone().mass_properties.principal_moments_body().x(), m = mass();
  const double alpha0 = 50 * M_PI / 180, rate0 = 33.0;
  const double e0 = 0.5 * (i1 + m * kA * kA * std::pow(std::cos(alpha0), 2)) * rate0 * rate0 +
                    m * kG * kA * std::sin(alpha0);
  auto rate_sq = [&](double alpha) {
    return 2 * (e0 - m * kG * kA * std::sin(alpha)) /
           (i1 + m * kA * kA * std::pow(std::cos(alpha), 2));
  };
  auto margin = [&](double alpha) { return kG - kA * std::sin(alpha) * rate_sq(alpha); };
  double lo = alpha0, hi = 80 * M_PI / 180;
  for (int i = 0; i < 200; ++i) (margin(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double alpha_lift = 0.5 * (lo + hi);
  const double t0 = 0.25;
  const double t_lift =
      t0 + boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
               [&](double a) { return 1 / std::sqrt(rate_sq(a)); }, alpha0, alpha_lift, 15, 1e-15);

  const Quaterniond q(Eigen::AngleAxisd(alpha0, Vector3d::UnitY()));
  vg::World world(config(0.5, 0.0, 0.0, 0.0), touching_top(q, Vector3d(0, rate0, 0)), t0);
  const WorldRun r = run(world, t0 + 0.2, 1e-3);
  ASSERT_GE(r.events.size(), 3u);
  EXPECT_EQ(r.events[0].kind, WorldEventKind::rim);  // the contact starts on the rim
  EXPECT_EQ(r.events[0].time_s, t0);
  EXPECT_EQ(r.events[1].kind, WorldEventKind::lift_off);
  EXPECT_NEAR(r.events[1].time_s, t_lift, 1e-12);
  // Next: an impact, later, in free flight from the lift-off state.
  EXPECT_EQ(r.events[2].kind, WorldEventKind::impact);
  EXPECT_GT(r.events[2].time_s, t_lift + 1e-3);
  const vg::RigidBodyState& lift = r.events[1].state;
  for (std::size_t k = 0; k < r.times.size(); ++k) {
    if (r.times[k] <= t_lift || r.times[k] >= r.events[2].time_s) continue;
    const double tau = r.times[k] - t_lift;
    EXPECT_LE((r.states[k].position_world -
               (lift.position_world + lift.velocity_world * tau + 0.5 * kGravity * tau * tau))
                  .norm(),
              1e-12);
  }
  EXPECT_GE(r.worst_gap, -1e-12);
  r.expect_no_energy_gain();
  std::printf("[ lift    ] lift-off at %.12f s (quadrature %.12f s), next impact %.3f ms later\n",
              r.events[1].time_s, t_lift, 1e3 * (r.events[2].time_s - t_lift));
}

TEST(WorldRest, AStonePlacedRestingOnTheBoardRestsAtOnce) {
  // Flat on the board, still: the first advance reports rest at the start time, no work after.
  vg::World world(config(0.5), at(Vector3d(0.1, 0.1, kC)), 2.0);
  std::vector<vg::WorldEvent> events;
  world.advance_to(2.0, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, WorldEventKind::rest);
  EXPECT_EQ(events[0].time_s, 2.0);
  EXPECT_TRUE(world.is_resting(0));
  // A command putting it back where it rests: woken and at rest again at once.
  events.clear();
  world.set_state(0, world.state(0), 3.0, events);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, WorldEventKind::wake);
  EXPECT_EQ(events[1].kind, WorldEventKind::rest);
  EXPECT_EQ(events[1].time_s, 3.0);
}

TEST(WorldStones, StonesAreIndependentAndTheirEventsMergeInTimeOrder) {
  // Two drops of different heights: each follows its own closed form; the events of both come
  // in time order; the first one's rest costs nothing while the second still bounces.
  const std::vector<vg::RigidBodyState> stones{at(Vector3d(-0.1, 0, kC + 0.01)),
                                               at(Vector3d(0.1, 0, kC + 0.05))};
  vg::World world(config(0.5), stones, 0.0);
  ASSERT_EQ(world.stone_count(), 2u);
  std::vector<vg::WorldEvent> events;
  for (int k = 1; k <= 400; ++k) world.advance_to(k * 1e-3, events);
  double previous = -1;
  int impacts[2] = {0, 0};
  for (const auto& e : events) {
    EXPECT_GE(e.time_s, previous);
    previous = e.time_s;
    if (e.kind == WorldEventKind::impact) ++impacts[e.stone];
  }
  EXPECT_EQ(impacts[0], static_cast<int>(drop_closed_form(0.5, 0.01).impact_times.size()));
  EXPECT_EQ(impacts[1], static_cast<int>(drop_closed_form(0.5, 0.05).impact_times.size()));
  EXPECT_NEAR(events.front().time_s, std::sqrt(2 * 0.01 / kG), 1e-12);
  EXPECT_EQ(events.front().stone, 0u);
  EXPECT_TRUE(world.all_resting());
}

}  // namespace
