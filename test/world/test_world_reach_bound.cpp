// The reach bound of advance_to's stage 1a (World::reach_bounds_of): a stone whose reach over a
// call meets no other stone is handled alone, so every point of its lens must stay inside that
// box for the whole call. The bound is argued (energy never rises, so the centre moves at most
// at sqrt(2 K / m) with K the energy above the lowest place the lens can lie; a stone the
// fallback or an island moves may also jump), not proven; this test tries it on thousands of
// random stones (fixed seed): in flight, landing and bouncing, in plane contact sliding,
// rolling and spinning, spinning on the rim, sliding off the board's edges, on the table, and
// pairs of touching stones in an island. Each stone's true motion is sampled finely over the
// call (64 samples and every event's exact state) and its lens, from the test's own support
// mapping, is checked against the box along the six axis directions.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "world/world_test_support.h"

namespace {

using namespace worldtest;

// Uniform in [lo, hi) from the raw 64-bit output (the same on every standard library).
struct Random {
  std::mt19937_64 engine{20261128};
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
  }
  Vector3d in_ball(double radius) {
    for (;;) {
      const Vector3d v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (v.squaredNorm() <= 1.0) return radius * v;
    }
  }
  Vector3d unit() {
    for (;;) {
      const Vector3d v = in_ball(1.0);
      if (v.norm() > 0.1) return v.normalized();
    }
  }
};

enum class Kind { flight, landing, plane, rim_spin, edge, table, island, kinds };

// The lens's lowest point on the plane z = h (the test's own support mapping).
vg::RigidBodyState on_plane(vg::RigidBodyState s, double h) {
  s.position_world.z() = 0.0;
  s.position_world.z() = h + lens_ref(s).reach(Vector3d::UnitZ());
  return s;
}

Quaterniond tilted(Random& r, double tilt_rad) {
  const double phi = r.uniform(0, 2 * M_PI);
  return Quaterniond(Eigen::AngleAxisd(tilt_rad, Vector3d(std::cos(phi), std::sin(phi), 0.0)));
}

// A random stone of the kind (and, for an island, its resting partner).
std::vector<vg::RigidBodyState> random_stones(Random& r, Kind kind) {
  vg::RigidBodyState s;
  switch (kind) {
    case Kind::flight:
      s = at(Vector3d(r.uniform(-0.3, 0.3), r.uniform(-0.3, 0.3), r.uniform(0.02, 0.2)),
             Quaterniond(Eigen::AngleAxisd(r.uniform(0, M_PI), r.unit())), r.in_ball(1.5));
      return {with_omega(s, r.in_ball(60.0))};
    case Kind::landing:
      s = on_plane(at(Vector3d(r.uniform(-0.19, 0.19), r.uniform(-0.2, 0.2), 0.0),
                      tilted(r, r.uniform(0, 1.5))),
                   r.uniform(0.0, 0.003));
      s.velocity_world = r.in_ball(0.5) - Vector3d(0, 0, r.uniform(0.0, 1.0));
      return {with_omega(s, r.in_ball(30.0))};
    case Kind::plane:
      s = on_plane(at(Vector3d(r.uniform(-0.18, 0.18), r.uniform(-0.2, 0.2), 0.0),
                      tilted(r, r.uniform(0, 0.2))),
                   0.0);
      s.velocity_world = Vector3d(r.uniform(-0.5, 0.5), r.uniform(-0.5, 0.5), 0.0);
      return {with_omega(s, Vector3d(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-60, 60)))};
    case Kind::rim_spin:
      s = on_plane(at(Vector3d(r.uniform(-0.18, 0.18), r.uniform(-0.2, 0.2), 0.0),
                      tilted(r, r.uniform(1.2, 1.55))),
                   r.uniform(0.0, 1e-4));
      return {with_omega(s, Vector3d(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-80, 80)))};
    case Kind::edge: {
      // Centre from a rim inside to half a rim beyond a side, sliding or falling outwards.
      const bool along_x = r.uniform(0, 1) < 0.5;
      const double sign = r.uniform(0, 1) < 0.5 ? -1.0 : 1.0;
      const double half = along_x ? kHalfX : kHalfY;
      const double out = sign * (half + r.uniform(-kA, 0.5 * kA));
      const double along = r.uniform(-0.15, 0.15);
      s = on_plane(at(along_x ? Vector3d(out, along, 0) : Vector3d(along, out, 0),
                      tilted(r, r.uniform(0, 0.3))),
                   r.uniform(0.0, 0.002));
      Vector3d v = r.in_ball(0.3);
      (along_x ? v.x() : v.y()) = sign * r.uniform(0.0, 0.6);
      s.velocity_world = v;
      return {with_omega(s, r.in_ball(20.0))};
    }
    case Kind::table:
      s = on_plane(at(Vector3d(r.uniform(kHalfX + 0.02, kHalfX + 0.1), r.uniform(-0.2, 0.2), 0.0),
                      tilted(r, r.uniform(0, 0.3))),
                   -kThickness + r.uniform(0.0, 0.01));
      s.velocity_world = r.in_ball(0.6);
      return {with_omega(s, r.in_ball(40.0))};
    case Kind::island: {
      // A flat stone at rest and a second one set down against it (centres one rim apart and
      // a little closer: touching) or dropped onto its edge, both made to push.
      const Vector3d c(r.uniform(-0.15, 0.15), r.uniform(-0.15, 0.15), 0.0);
      const vg::RigidBodyState base = on_plane(at(c), 0.0);
      const double phi = r.uniform(0, 2 * M_PI);
      const Vector3d u(std::cos(phi), std::sin(phi), 0.0);
      if (r.uniform(0, 1) < 0.5) {
        s = on_plane(at(c + (2 * kA + 1e-10) * u), 0.0);
        s.velocity_world = -r.uniform(0.01, 0.3) * u;
        s = with_omega(s, Vector3d(0, 0, r.uniform(-20, 20)));
      } else {
        s = on_plane(at(c + r.uniform(1.2, 1.8) * kA * u), 2 * kC + r.uniform(0.0, 0.003));
        s.velocity_world = Vector3d(0, 0, -r.uniform(0.0, 0.5));
      }
      return {base, s};
    }
    case Kind::kinds:
      break;
  }
  return {};
}

// How far every point of the lens stays inside the box (m; negative: outside), along the six
// axis directions.
double slack(const vg::RigidBodyState& s, const vg::Bounds& box) {
  const vgtest::LensReference lens = lens_ref(s);
  double smallest = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const Vector3d e = Vector3d::Unit(axis);
    smallest = std::min(smallest, box.upper[axis] - lens.support(e)[axis]);
    smallest = std::min(smallest, lens.support(-e)[axis] - box.lower[axis]);
  }
  return smallest;
}

TEST(WorldReachBound, EveryPointOfARandomStoneStaysInItsReachOverTheCall) {
  Random r;
  const int cases = 3000, samples = 64;
  const double calls_s[] = {1e-3, 1.0 / 60.0, 0.05};
  double worst_slack = std::numeric_limits<double>::infinity();
  // Per kind: the largest share of the motion allowance used.
  std::vector<double> worst_used(static_cast<int>(Kind::kinds), -1.0);
  long checked = 0, skipped = 0;
  std::vector<long> in_mode(4, 0);  // stones sampled in each mode (flight .. resting)
  long impacts = 0, islands = 0;
  for (int n = 0; n < cases; ++n) {
    const Kind kind = static_cast<Kind>(n % static_cast<int>(Kind::kinds));
    const std::vector<vg::RigidBodyState> stones = random_stones(r, kind);
    vg::WorldConfig c = config(r.uniform(0.1, 0.8), r.uniform(0.1, 0.6));
    c.stone_contact = kind == Kind::island;
    std::optional<vg::World> world;
    try {
      world.emplace(c, stones, 0.0);
    } catch (const vg::InvalidArgument&) {
      ++skipped;  // a random pose overlapping the board beyond the tolerance
      continue;
    }
    std::vector<vg::WorldEvent> events;
    // Into the motion first: a random while, so the call starts in any phase. A pair settles in
    // 0.1 to 0.2 s (its island rests only where the contacts hold both stones), the others'
    // phases come sooner.
    world->advance_to(r.uniform(0.0, 0.03) * (kind == Kind::island ? 10.0 : 1.0), events);
    const double t0 = world->time(), dt = calls_s[n % 3];
    std::vector<vg::Bounds> boxes;
    for (const vg::StoneId id : world->stone_ids()) {
      boxes.push_back(world->reach_bounds_of(id, dt));
    }
    islands += world->counters().islands_formed > 0 ? 1 : 0;
    const long impacts_before = world->counters().impacts;
    const auto check = [&](std::size_t k, const vg::RigidBodyState& s, double t) {
      const double gap = slack(s, boxes[k]);
      // The box's half side R = a + (motion allowance); the lens reached R - gap from the
      // centre at the call's start along some axis, (R - gap - a) / (R - a) of the allowance.
      const double half_side = 0.5 * (boxes[k].upper.x() - boxes[k].lower.x());
      const double allowance = half_side - kA;
      const double used = (half_side - gap - kA) / allowance;
      worst_slack = std::min(worst_slack, gap);
      if (allowance > 1e-9) {
        double& w = worst_used[static_cast<int>(kind)];
        w = std::max(w, used);
      }
      ++checked;
      EXPECT_GE(gap, -1e-12) << "case " << n << " (kind " << static_cast<int>(kind) << "), stone "
                             << k << " at t0 + " << t - t0 << " s of a " << dt
                             << " s call: outside its reach by " << -gap << " m";
    };
    // The bound is for a stone awake at the call's start, and holds until it meets a stone
    // outside its island (the pass ends there and the world bounds it anew): an event naming
    // another stone ends the watch of both (its own state, at the instant, still counts).
    std::vector<char> watched(world->stone_count());
    for (std::size_t i = 0; i < watched.size(); ++i) watched[i] = !world->is_resting(i);
    events.clear();
    for (int k = 1; k <= samples; ++k) {
      world->advance_to(t0 + dt * k / samples, events);
      for (const vg::WorldEvent& e : events) {
        const std::size_t i = world->index_of(e.id);
        if (watched[i]) check(i, e.state, e.time_s);
        if (e.other && e.time_s > t0) {
          watched[i] = 0;
          watched[world->index_of(*e.other)] = 0;
        }
      }
      events.clear();
      for (std::size_t i = 0; i < world->stone_count(); ++i) {
        if (!watched[i]) continue;
        check(i, world->state(i), world->time());
        ++in_mode[static_cast<int>(world->mode(i))];
      }
    }
    impacts += world->counters().impacts - impacts_before;
  }
  std::cout << "reach bound: " << cases << " cases (" << skipped << " skipped), " << checked
            << " poses checked; smallest slack " << worst_slack << " m; largest share of the "
            << "motion allowance used (flight, landing, plane, rim spin, edge, table, island):";
  for (const double w : worst_used) std::cout << " " << w;
  std::cout << "; samples in flight " << in_mode[0] << ", plane contact " << in_mode[1]
            << ", fallback " << in_mode[2] << ", resting " << in_mode[3] << "; impacts " << impacts
            << ", cases with an island " << islands << "\n";
  // The cases cover every mode and the scene's interactions.
  EXPECT_LT(skipped, cases / 20);
  for (int m = 0; m < 3; ++m) EXPECT_GT(in_mode[m], 10000) << "mode " << m;
  EXPECT_GT(in_mode[3], 0);  // came to rest within the call
  EXPECT_GT(impacts, 100);
  EXPECT_GT(islands, 50);
}

}  // namespace
