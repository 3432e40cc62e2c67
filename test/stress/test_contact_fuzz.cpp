// Seeded fuzz of the contact core (issue 19): random states in every regime the node accepts
// (flight onto the board, onto the table, at the board's edges, corners and sides; a stone
// rolling on its rim; spins up to the node's bound of 500 rad/s; physically zero speeds,
// denormal and tiny components) with random materials inside the node's limits
// (sim/stone_config: restitution [0, 1], friction [0, 0.9], rolling and spinning lengths
// [0, 5e-4] and [0, 1] m, Zeno height (0, 1e-3] m), each advanced 2 s on a 0.05 s grid with a work
// budget per call. Checked in every sampled state and event: no exception, finite states, unit
// quaternions, no overlap beyond 1e-12 m (measured by an independent BoardDistance query, the
// geometry tested in test_board_distance), the energy never above the energy at the start beyond
// round-off (1e-12 of |E| + m g a: the guards hold the energy at step ends; dense-output samples
// inside a step are exact to ~1e-13 relative), and the work per state bounded. VG_FUZZ_STATES sets
// the number of states: 1000 by default (38 s here). The 10^4 took 506 s and found state
// 1930 (spin) needing 244,573 work units in 2 s, above kMaxWorkPerState: an open finding,
// reproduced alone with VG_FUZZ_FIRST=1930 VG_FUZZ_STATES=1931 (VG_FUZZ_FIRST skips the runs, not
// the draws, of the states before it; VG_FUZZ_VERBOSE=1 prints each state's events, material and
// counters). It is a stone spinning at 462 rad/s upright on its rim: about 50 plane-contact steps
// per millisecond while the contact point sticks and up to 460 in the millisecond after each of
// its 265 slip starts (the slip direction turns at mu g / |v|), i.e. issue 17's cost, not a stall
// (a stall made tens of thousands of steps per millisecond).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/sim/stone_config.h"  // the node's material bounds (constants only)
#include "virtual_go/world/world.h"
#include "world/world_test_support.h"

namespace vg = virtual_go;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kG = 9.80665;
constexpr double kHalfX = 0.4242 / 2, kHalfY = 0.4545 / 2, kThickness = 0.1515;
constexpr double kA = 0.011, kC = 0.0046;  // size 33: half width, half height
constexpr double kMaxOmega = 500.0;        // rad/s, the node's ~max_angular_velocity
constexpr double kDuration = 2.0, kTick = 0.05;
constexpr long kBudgetPerCall = 20000;
// Work (WorldCounters::work) one state may take over the 2 s: far above the worst seen (see the
// printed figure), far below the tens of thousands of steps per millisecond of the stalls.
constexpr long kMaxWorkPerState = 200000;

enum class Regime { board, table, edge, rim, spin, tiny, count };
const char* regime_name(Regime r) {
  static const char* names[] = {"board", "table", "edge", "rim", "spin", "tiny"};
  return names[static_cast<int>(r)];
}

struct Rng {
  std::mt19937_64 engine;
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(engine);
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  Vector3d in_ball(double radius) {
    Vector3d v;
    do v = Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    while (v.squaredNorm() > 1.0);
    return radius * v;
  }
  Quaterniond orientation() { return Quaterniond::UnitRandom(); }  // uses std::rand: seeded below
  // A length in [0, 1] m: zero, the limit, or log-uniform over 12 decades.
  // A couple arm in [0, max_m], its ends included.
  double length(double max_m) {
    const double u = uniform(0, 1);
    return u < 0.1 ? 0.0 : u < 0.2 ? max_m : log_uniform(1e-12, max_m);
  }
  // A component physically zero: denormal, 1e-300, 1e-200, or exactly 0.
  double tiny() {
    static const double values[] = {4.9e-324, 1e-310, 1e-300, 1e-200, 1e-160, 1e-20, 0.0};
    const double v = values[engine() % 7];
    return chance(0.5) ? -v : v;
  }
};

vg::ContactMaterial random_material(Rng& rng) {
  vg::ContactMaterial m;
  const double u = rng.uniform(0, 1);
  m.restitution = u < 0.1 ? 0.0 : u < 0.2 ? 1.0 : rng.uniform(0, 1);
  const double f = rng.uniform(0, 1);
  m.friction = f < 0.1 ? 0.0 : f < 0.2 ? 0.9 : f < 0.25 ? 1e-300 : rng.uniform(0, 0.9);
  m.rolling_resistance_m = rng.length(vg::kMaxNodeRollingResistanceM);
  m.spinning_friction_m = rng.length(vg::kMaxNodeSpinningFrictionM);
  return m;
}

vg::WorldConfig random_config(Rng& rng, const vg::Stone& stone) {
  vg::WorldConfig c(
      vg::MotionSetup{vg::MotionModel(vg::MotionModelKind::rigid_body, stone.mass_properties),
                      Vector3d(0, 0, -kG)},
      stone.shape);
  c.board.size_x_m = 2 * kHalfX;
  c.board.size_y_m = 2 * kHalfY;
  c.board.thickness_m = kThickness;
  c.board_material = random_material(rng);
  c.table_material = random_material(rng);
  c.zeno_height_m = rng.chance(0.2) ? 1e-3 : rng.log_uniform(1e-9, 1e-3);
  return c;
}

vg::RigidBodyState random_state(Rng& rng, Regime regime, const vg::MotionModel& model) {
  vg::RigidBodyState s;
  Vector3d omega = rng.in_ball(rng.chance(0.3) ? kMaxOmega : 50.0);
  s.orientation = rng.orientation();
  s.velocity_world = rng.in_ball(2.0);
  switch (regime) {
    case Regime::board:
      s.position_world = Vector3d(rng.uniform(-kHalfX, kHalfX), rng.uniform(-kHalfY, kHalfY),
                                  kA + rng.uniform(0, 0.2));
      break;
    case Regime::table: {
      const double x =
          rng.chance(0.5) ? rng.uniform(kHalfX + kA, kHalfX + 0.1) : rng.uniform(-kHalfX, kHalfX);
      const double y = std::abs(x) > kHalfX ? rng.uniform(-kHalfY - 0.1, kHalfY + 0.1)
                                            : rng.uniform(kHalfY + kA, kHalfY + 0.1);
      s.position_world = Vector3d(rng.chance(0.5) ? x : -x, rng.chance(0.5) ? y : -y,
                                  -kThickness + kA + rng.uniform(0, 0.2));
      s.velocity_world.head<2>() *= 0.3;  // mostly towards the sides or the table
      break;
    }
    case Regime::edge: {
      // Near an edge or a corner, above, beside or below the top face.
      const bool corner = rng.chance(0.3);
      const double x = corner || rng.chance(0.5) ? kHalfX + rng.uniform(-0.01, kA + 0.01)
                                                 : rng.uniform(-kHalfX, kHalfX);
      const double y = corner || std::abs(x) < kHalfX ? kHalfY + rng.uniform(-0.01, kA + 0.01)
                                                      : rng.uniform(-kHalfY, kHalfY);
      s.position_world = Vector3d(rng.chance(0.5) ? x : -x, rng.chance(0.5) ? y : -y,
                                  rng.uniform(-kThickness + kA, 0.03));
      break;
    }
    case Regime::rim: {
      // Upright on the rim (axis horizontal), touching the board, rolling about its axis.
      const double heading = rng.uniform(0, 2 * M_PI);
      const Vector3d axis(std::cos(heading), std::sin(heading), rng.uniform(-0.05, 0.05));
      s.orientation = Quaterniond::FromTwoVectors(Vector3d::UnitZ(), axis.normalized());
      const bool table = rng.chance(0.2);
      s.position_world =
          table ? Vector3d(kHalfX + 0.05, rng.uniform(-kHalfY, kHalfY), -kThickness + kA + 1e-3)
                : Vector3d(rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15),
                           kA + rng.uniform(0, 1e-3));
      const double roll = rng.uniform(-100, 100);
      omega = roll * axis.normalized() + rng.in_ball(20.0);
      s.velocity_world = omega.cross(Vector3d(0, 0, kA)) + rng.in_ball(0.05);
      s.velocity_world.z() = rng.uniform(-0.1, 0.1);
      break;
    }
    case Regime::spin:
      s.position_world =
          Vector3d(rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15), kA + rng.uniform(0, 0.05));
      omega = rng.chance(0.5) ? Vector3d(0, 0, rng.chance(0.5) ? kMaxOmega : -kMaxOmega)
                              : kMaxOmega * rng.in_ball(1.0).normalized();
      s.velocity_world = rng.in_ball(0.5);
      break;
    case Regime::tiny:
      // Resting flat on the board (gap 0) or slightly above, with physically zero motion.
      s.orientation = rng.chance(0.5) ? Quaterniond::Identity() : s.orientation;
      s.position_world = Vector3d(rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15),
                                  s.orientation.w() == 1.0 ? kC : kA + rng.uniform(0, 1e-3));
      s.velocity_world = Vector3d(rng.tiny(), rng.tiny(), rng.tiny());
      omega = Vector3d(rng.tiny(), rng.tiny(), rng.tiny());
      break;
    case Regime::count:
      break;
  }
  s.angular_momentum_world = model.angular_momentum_world(s.orientation, omega);
  return s;
}

struct Worst {
  long states = 0, rejected_placements = 0, budget_stops = 0;
  long max_work = 0, total_work = 0;
  double min_gap = std::numeric_limits<double>::infinity();
  double max_energy_rise = -std::numeric_limits<double>::infinity();  // relative to the scale
  double max_step_rise = -std::numeric_limits<double>::infinity();    // over the state before
};

TEST(ContactFuzz, EveryRegimeEveryMaterialNoFailureNoStallNoOverlapNoEnergyGain) {
  const char* env = std::getenv("VG_FUZZ_STATES");
  const long states = env ? std::atol(env) : 1000;
  ASSERT_GT(states, 0);
  // VG_FUZZ_FIRST skips the runs (not the draws) of the states before it: one state reproduced
  // alone.
  const char* first_env = std::getenv("VG_FUZZ_FIRST");
  const long first = first_env ? std::atol(first_env) : 0;
  std::srand(19);  // Quaterniond::UnitRandom
  Rng rng{std::mt19937_64(19)};
  const vg::Stone stone = vg::make_stone(vg::StoneSpec{});  // size 33, 22 mm: the node's default
  const vg::MotionModel model(vg::MotionModelKind::rigid_body, stone.mass_properties);
  const double mass = worldtest::mass();
  const auto wall_start = std::chrono::steady_clock::now();
  Worst worst;
  std::vector<vg::WorldEvent> events;
  for (long n = 0; n < states; ++n) {
    const Regime regime = static_cast<Regime>(n % static_cast<long>(Regime::count));
    const vg::WorldConfig config = random_config(rng, stone);
    const vg::BoardDistance board(vg::LensGeometry(config.shape), config.board);
    vg::RigidBodyState s0 = random_state(rng, regime, model);
    if (n < first) continue;
    // Lift a placement that overlaps the board or the table until the World accepts it.
    std::optional<vg::World> world;
    for (int lift = 0; lift < 200 && !world; ++lift) {
      try {
        world.emplace(config, s0, 0.0);
      } catch (const vg::InvalidArgument&) {
        ++worst.rejected_placements;
        s0.position_world.z() += 1e-3;
      }
    }
    ASSERT_TRUE(world) << "state " << n << " (" << regime_name(regime) << ") never placed";
    const double e0 = worldtest::energy(s0);  // the test's own energy (world_test_support.h)
    const double scale = std::abs(e0) + mass * kG * kA;
    double e_before = e0;
    const std::string what = "state " + std::to_string(n) + " (" + regime_name(regime) + ")";
    auto check = [&](const vg::RigidBodyState& s, double t) {
      ASSERT_TRUE(s.position_world.allFinite() && s.velocity_world.allFinite() &&
                  s.angular_momentum_world.allFinite() && s.orientation.coeffs().allFinite())
          << what << " at t = " << t;
      ASSERT_NEAR(s.orientation.norm(), 1.0, 1e-12) << what << " at t = " << t;
      const vg::BoardContact c = board.nearest(s);
      worst.min_gap = std::min(worst.min_gap, c.lens.gap_m);
      ASSERT_GE(c.lens.gap_m, -1e-12) << what << " at t = " << t;
      // Asserted: never above the start. Reported: the largest rise over the state before
      // (events and samples in time order), an open finding: 1.4e-12 of the scale in the first
      // 1000 states, all at plane-contact events (slip start, cap/rim switches) and impacts. The
      // fallback's settle lift (up to 1.7e-8 before the island fallback) is gone.
      const double energy = worldtest::energy(s);
      const double rise = (energy - e0) / scale;
      worst.max_energy_rise = std::max(worst.max_energy_rise, rise);
      worst.max_step_rise = std::max(worst.max_step_rise, (energy - e_before) / scale);
      e_before = energy;
      ASSERT_LE(rise, 1e-12) << what << " at t = " << t;
    };
    long calls = 0;
    for (double target = kTick; world->time() < kDuration; ++calls) {
      ASSERT_LT(calls, 10 * static_cast<long>(kDuration / kTick)) << what << ": no progress";
      events.clear();
      vg::AdvanceResult r;
      try {
        r = world->advance_to(std::min(target, kDuration), events, vg::WorkBudget{kBudgetPerCall});
      } catch (const std::exception& e) {
        FAIL() << what << " at t = " << world->time() << ": " << e.what();
      }
      if (!r.reached) ++worst.budget_stops;
      ASSERT_LE(r.work, 2 * kBudgetPerCall + 200000) << what;
      for (const vg::WorldEvent& e : events) {
        if (std::getenv("VG_FUZZ_VERBOSE"))
          std::printf("  %.9f %s/%s\n", e.time_s, vg::world_event_kind_name(e.kind).c_str(),
                      vg::world_event_detail_name(e.detail).c_str());
        check(e.state, e.time_s);
      }
      check(world->state(0), world->time());
      if (r.reached) target += kTick;
    }
    const long work = world->counters().work();
    if (std::getenv("VG_FUZZ_VERBOSE")) {
      const auto& bm = config.board_material;
      std::printf("board e %.3g mu %.3g lr %.3g ls %.3g zeno %.3g; v %s w-L %s\n", bm.restitution,
                  bm.friction, bm.rolling_resistance_m, bm.spinning_friction_m,
                  config.zeno_height_m, vg::format_vector(s0.velocity_world).c_str(),
                  vg::format_vector(s0.angular_momentum_world).c_str());
      const vg::RigidBodyState& sf = world->state(0);
      std::printf("end v %s L %s pos %s\n", vg::format_vector(sf.velocity_world).c_str(),
                  vg::format_vector(sf.angular_momentum_world).c_str(),
                  vg::format_vector(sf.position_world).c_str());
      const vg::WorldCounters& k = world->counters();
      std::printf(
          "%s: searches %ld (+%ld steps), impacts %ld (+%ld slip), plane %ld (%ld rhs), "
          "nonsmooth %ld, events %ld\n",
          what.c_str(), k.contact_searches, k.contact_search_steps, k.impacts, k.impact_slip_steps,
          k.plane_contact_steps, k.plane_contact_rhs, k.nonsmooth_steps, k.events);
    }
    EXPECT_LE(work, kMaxWorkPerState) << what;
    worst.max_work = std::max(worst.max_work, work);
    worst.total_work += work;
    ++worst.states;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::printf(
      "contact fuzz: %ld states x 2 s in %.1f s; work per state max %ld, mean %.0f; %ld budget "
      "stops; %ld placements lifted; smallest gap %.3g m; largest energy rise %.3g of the "
      "scale over the start, %.3g over the state before\n",
      worst.states, wall, worst.max_work,
      static_cast<double>(worst.total_work) / static_cast<double>(worst.states), worst.budget_stops,
      worst.rejected_placements, worst.min_gap, worst.max_energy_rise, worst.max_step_rise);
}

}  // namespace
