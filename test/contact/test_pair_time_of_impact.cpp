// Time of first contact between two stones against an independent root: the test's own
// closed-form flights (support/flight_reference.h) and GJK on the lens's support mapping
// (support/convex_reference.h), a dense scan for the first overlapping time and bisection on
// it; a closed form for two stones sliding head-on; a flight onto a resting stone, and onto a
// stone sliding (supported, spinning about its axis) or leaning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "support/flight_reference.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/pair_time_of_impact.h"

namespace vg = virtual_go;

namespace {

constexpr double kAa = 0.0111, kAb = 0.01095, kC = 0.0046, kG = 9.80665;

struct Fixture {
  vg::LensShape shape_a{2 * kAa, 2 * kC}, shape_b{2 * kAb, 2 * kC};
  vg::LensGeometry lens_a{shape_a}, lens_b{shape_b};
  vg::MassProperties mp_a = vg::MassProperties::of_lens(shape_a, 2700.0);
  vg::MassProperties mp_b = vg::MassProperties::of_lens(shape_b, 2700.0);
  vg::MotionSetup setup_a{vg::MotionModel(vg::MotionModelKind::rigid_body, mp_a),
                          Eigen::Vector3d(0, 0, -kG)};
  vg::MotionSetup setup_b{vg::MotionModel(vg::MotionModelKind::rigid_body, mp_b),
                          Eigen::Vector3d(0, 0, -kG)};
  std::mt19937 rng{4242};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};

  Eigen::Vector3d random_unit() {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  }

  struct Throw {
    vg::RigidBodyState state;
    vgtest::FlightReference flight;
  };
  static Throw make_throw(const vg::MotionSetup& setup, double a, const Eigen::Vector3d& g,
                          const Eigen::Vector3d& x, const Eigen::Vector3d& v, const vgtest::Quat& q,
                          const Eigen::Vector3d& omega_world) {
    Throw th{vg::RigidBodyState(), vgtest::FlightReference{a, kC, x, v, g, {}}};
    th.state.position_world = x;
    th.state.velocity_world = v;
    th.state.orientation = vgtest::to_eigen(q);
    th.state.angular_momentum_world =
        setup.model.angular_momentum_world(th.state.orientation, omega_world);
    const Eigen::Vector3d moments = setup.model.mass_properties().principal_moments_body();
    th.flight.top =
        vgtest::AxisymmetricTop{moments.x(), moments.z(), q, th.state.angular_momentum_world};
    return th;
  }
};

// The reference says the lenses overlap (or touch) at time t.
bool overlapping(const vgtest::FlightReference& fa, const vgtest::FlightReference& fb, double t) {
  const vgtest::GjkResult r = vgtest::gjk_distance(fa.lens_at(t), fb.lens_at(t));
  return r.overlap || r.upper <= 0.0;
}

// First time of overlap on [0, t_max]: a scan every dt (0.4 ms: contacts last milliseconds), then
// 80 bisections. -1 if none seen.
double reference_first_contact(const vgtest::FlightReference& fa, const vgtest::FlightReference& fb,
                               double t_max, double dt) {
  double lo = 0.0;
  for (double hi = dt; hi <= t_max + dt; hi += dt) {
    if (!overlapping(fa, fb, hi)) {
      lo = hi;
      continue;
    }
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (lo + hi);
      (overlapping(fa, fb, mid) ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
  }
  return -1.0;
}

double reference_distance(const vgtest::FlightReference& fa, const vgtest::FlightReference& fb,
                          double t) {
  return vgtest::gjk_distance(fa.lens_at(t), fb.lens_at(t)).upper;
}

}  // namespace

TEST(PairTimeOfImpact, HeadOnSlideIsTheClosedForm) {
  // Two flat stones flying side by side at the same height towards each other: gravity cancels,
  // the rims meet after (|dx| - a_A - a_B) / |dv|.
  Fixture f;
  const vgtest::Quat level(1, 0, 0, 0);
  const Eigen::Vector3d g(0, 0, -kG);
  const Fixture::Throw a =
      Fixture::make_throw(f.setup_a, kAa, g, Eigen::Vector3d(0, 0, 0.1),
                          Eigen::Vector3d(0.3, 0, 0.5), level, Eigen::Vector3d::Zero());
  const Fixture::Throw b = Fixture::make_throw(f.setup_b, kAb, g, Eigen::Vector3d(0.05, 0, 0.1),
                                               Eigen::Vector3d(-0.2, 0, 0.5), level,
                                               Eigen::Vector3d(0, 0, 80.0));  // spin: no effect
  const vg::PairTimeOfImpact toi = vg::pair_time_of_impact(
      {f.lens_a, f.setup_a, a.state}, {f.lens_b, f.setup_b, b.state}, 0.0, 1.0);
  ASSERT_TRUE(toi.hit);
  const double expected = (0.05 - kAa - kAb) / 0.5;
  EXPECT_NEAR(toi.time_s, expected, 1e-16);
  EXPECT_NEAR(toi.approach_speed_mps, 0.5, 1e-12);
  EXPECT_NEAR(toi.contact.normal_world.x(), 1.0, 1e-9);
  EXPECT_EQ(toi.contact.part_a, vg::LensPart::rim);
  EXPECT_EQ(toi.contact.part_b, vg::LensPart::rim);
  std::printf("[ measured ] head-on: |t - t*| %.3g s, %d advancement + %d polish steps\n",
              std::abs(toi.time_s - expected), toi.advancement_steps, toi.polish_steps);
}

TEST(PairTimeOfImpact, RandomSpinningPairsMatchAnIndependentRoot) {
  Fixture f;
  const Eigen::Vector3d g(0, 0, -kG);
  double worst_dt = 0.0, worst_gap = 0.0;
  int hits = 0, misses = 0, grazes = 0, steps = 0, polish = 0, most = 0;
  const int kPairs = 150;
  for (int k = 0; k < kPairs; ++k) {
    // A somewhere, B 30-50 mm away, aimed at A within +-10 mm, 0.2-2 m/s relative, both
    // tumbling at up to 60 rad/s, both under gravity.
    const Eigen::Vector3d xa(0.05 * f.normal(f.rng), 0.05 * f.normal(f.rng), 0.1);
    const Eigen::Vector3d xb = xa + (0.03 + 0.02 * f.uniform(f.rng)) * f.random_unit();
    const Eigen::Vector3d aim = xa + 0.01 * f.normal(f.rng) * f.random_unit();
    const Eigen::Vector3d va(0.3 * f.normal(f.rng), 0.3 * f.normal(f.rng), f.normal(f.rng));
    const Eigen::Vector3d vb = va + (0.2 + 1.8 * f.uniform(f.rng)) * (aim - xb).normalized();
    const Fixture::Throw a = Fixture::make_throw(
        f.setup_a, kAa, g, xa, va, vgtest::axis_angle(M_PI * f.uniform(f.rng) * f.random_unit()),
        60.0 * f.uniform(f.rng) * f.random_unit());
    const Fixture::Throw b = Fixture::make_throw(
        f.setup_b, kAb, g, xb, vb, vgtest::axis_angle(M_PI * f.uniform(f.rng) * f.random_unit()),
        60.0 * f.uniform(f.rng) * f.random_unit());
    if (overlapping(a.flight, b.flight, 0.0)) continue;
    const double horizon = 0.3;
    const vg::PairTimeOfImpact toi = vg::pair_time_of_impact(
        {f.lens_a, f.setup_a, a.state}, {f.lens_b, f.setup_b, b.state}, 0.0, horizon);
    const double t_ref = reference_first_contact(a.flight, b.flight, horizon, 4e-4);
    steps += toi.advancement_steps;
    polish += toi.polish_steps;
    most = std::max(most, toi.advancement_steps + toi.polish_steps);
    if (toi.hit) {
      // Never after the contact: the reference distance there is zero to round-off.
      const double d = reference_distance(a.flight, b.flight, toi.time_s);
      worst_gap = std::max(worst_gap, d);
      EXPECT_LT(d, 1e-14) << k;
      EXPECT_GT(toi.approach_speed_mps, 0.0) << k;
    }
    if (t_ref < 0.0) {
      // The scan saw no overlap: either none, or a graze between two samples that the search
      // found (the reference distance there is 0, checked above).
      if (toi.hit)
        ++grazes;
      else
        ++misses;
      continue;
    }
    ASSERT_TRUE(toi.hit) << k << " reference contact at " << t_ref;
    ++hits;
    if (toi.time_s < t_ref - 1e-12) {
      ++grazes;  // an earlier touch between scan samples: a real one (distance 0 above)
      continue;
    }
    worst_dt = std::max(worst_dt, std::abs(toi.time_s - t_ref));
  }
  const int searched = hits + misses + grazes;
  std::printf(
      "[ measured ] %d pairs: %d contacts matched, %d none, %d grazes between scan samples; "
      "max |t - t_ref| %.3g s, max reference distance at the hit %.3g m; steps mean %.1f "
      "(+%.1f polish), max %d\n",
      searched, hits, misses, grazes, worst_dt, worst_gap, double(steps) / searched,
      double(polish) / searched, most);
  EXPECT_GT(hits, 100);
  EXPECT_LT(worst_dt, 1e-12);
}

TEST(PairTimeOfImpact, FlightOntoARestingStone) {
  // A (white) rests flat on the board (supported: no gravity in its closed form); B (black)
  // drops onto it, tilted and spinning, from random heights and offsets.
  Fixture f;
  const Eigen::Vector3d g(0, 0, -kG);
  double worst_dt = 0.0;
  int hits = 0;
  for (int k = 0; k < 60; ++k) {
    const Fixture::Throw a = Fixture::make_throw(f.setup_b, kAb, Eigen::Vector3d::Zero(),
                                                 Eigen::Vector3d(0, 0, kC), Eigen::Vector3d::Zero(),
                                                 vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d::Zero());
    const Eigen::Vector3d xb(0.012 * f.normal(f.rng), 0.012 * f.normal(f.rng),
                             0.03 + 0.05 * f.uniform(f.rng));
    const Fixture::Throw b = Fixture::make_throw(
        f.setup_a, kAa, g, xb, Eigen::Vector3d(0.05 * f.normal(f.rng), 0.05 * f.normal(f.rng), 0),
        vgtest::axis_angle(0.6 * f.uniform(f.rng) * f.random_unit()),
        30.0 * f.uniform(f.rng) * f.random_unit());
    const vg::PairTimeOfImpact toi = vg::pair_time_of_impact(
        {f.lens_b, f.setup_b, a.state, 0.0, true}, {f.lens_a, f.setup_a, b.state}, 0.0, 0.2);
    const double t_ref = reference_first_contact(a.flight, b.flight, 0.2, 2e-4);
    if (t_ref < 0.0) {
      EXPECT_FALSE(toi.hit && reference_distance(a.flight, b.flight, toi.time_s) > 1e-14) << k;
      continue;
    }
    ASSERT_TRUE(toi.hit) << k;
    ++hits;
    worst_dt = std::max(worst_dt, std::abs(toi.time_s - t_ref));
    // The resting stone has not moved.
    EXPECT_EQ(toi.state_a.position_world, Eigen::Vector3d(0, 0, kC)) << k;
  }
  std::printf("[ measured ] onto a resting stone: %d hits, max |t - t_ref| %.3g s\n", hits,
              worst_dt);
  EXPECT_GT(hits, 30);
  EXPECT_LT(worst_dt, 1e-12);
}

TEST(PairTimeOfImpact, FlightOntoASlidingOrLeaningStone) {
  // A (white) is supported (no gravity in its closed form): sliding along the board (0.3 m/s
  // per axis, normal) and spinning about its own axis at up to 40 rad/s, or still; flat, or leaning
  // by up to 0.3 rad (as on a neighbour). B (black) is thrown at it, tilted and tumbling, from
  // 30-60 mm away and up to 40 mm above. Against the reference's first overlap (scan and
  // bisection), and with no overlap at any of 400 times before the contact found (a scan 25x finer
  // than the reference's, GJK on the test's lenses).
  Fixture f;
  const Eigen::Vector3d g(0, 0, -kG);
  double worst_dt = 0.0;
  int hits = 0, checked_before = 0;
  for (int k = 0; k < 80; ++k) {
    const bool leaning = k % 2 == 1, still = k % 5 == 0;
    Eigen::Vector3d axis_tilt = Eigen::Vector3d::Zero(), va = Eigen::Vector3d::Zero();
    if (leaning) {
      axis_tilt = 0.3 * f.uniform(f.rng) *
                  Eigen::Vector3d(f.normal(f.rng), f.normal(f.rng), 0).normalized();
    }
    const vgtest::Quat qa = vgtest::axis_angle(axis_tilt);
    const Eigen::Vector3d b_axis = vgtest::rotate(qa, Eigen::Vector3d::UnitZ());
    Eigen::Vector3d omega_a = Eigen::Vector3d::Zero();
    if (!still) {
      va = Eigen::Vector3d(0.3 * f.normal(f.rng), 0.3 * f.normal(f.rng), 0);
      omega_a = 40.0 * f.uniform(f.rng) * b_axis;
    }
    const Fixture::Throw a = Fixture::make_throw(f.setup_b, kAb, Eigen::Vector3d::Zero(),
                                                 Eigen::Vector3d(0, 0, kC), va, qa, omega_a);
    const double bearing = 2 * M_PI * f.uniform(f.rng);
    const Eigen::Vector3d xb = Eigen::Vector3d(std::cos(bearing), std::sin(bearing), 0) *
                                   (0.03 + 0.03 * f.uniform(f.rng)) +
                               Eigen::Vector3d(0, 0, kC + 0.04 * f.uniform(f.rng));
    // Aimed where A will be about 40 ms later (within 8 mm), at 0.5-1.5 m/s.
    const Eigen::Vector3d target =
        a.state.position_world + 0.04 * va + 0.008 * f.normal(f.rng) * f.random_unit();
    const Eigen::Vector3d vb = (0.5 + f.uniform(f.rng)) * (target - xb).normalized();
    const Fixture::Throw b = Fixture::make_throw(
        f.setup_a, kAa, g, xb, vb, vgtest::axis_angle(M_PI * f.uniform(f.rng) * f.random_unit()),
        40.0 * f.uniform(f.rng) * f.random_unit());
    if (overlapping(a.flight, b.flight, 0.0)) continue;
    const double horizon = 0.2;
    const vg::PairTimeOfImpact toi = vg::pair_time_of_impact(
        {f.lens_b, f.setup_b, a.state, 0.0, true}, {f.lens_a, f.setup_a, b.state}, 0.0, horizon);
    const double t_ref = reference_first_contact(a.flight, b.flight, horizon, 4e-4);
    if (toi.hit) {
      EXPECT_LT(reference_distance(a.flight, b.flight, toi.time_s), 1e-14) << k;
      for (int s = 0; s < 400; ++s) {
        const double t = toi.time_s * s / 400.0;
        EXPECT_FALSE(overlapping(a.flight, b.flight, t)) << k << " overlap at " << t;
      }
      ++checked_before;
    }
    if (t_ref < 0.0) continue;  // none seen by the reference (a graze is checked above)
    ASSERT_TRUE(toi.hit) << k << " reference contact at " << t_ref;
    ++hits;
    if (toi.time_s < t_ref - 1e-12) continue;  // an earlier graze between scan samples
    worst_dt = std::max(worst_dt, std::abs(toi.time_s - t_ref));
  }
  std::printf(
      "[ measured ] onto a sliding or leaning stone: %d hits matched, %d contacts checked "
      "free before; max |t - t_ref| %.3g s\n",
      hits, checked_before, worst_dt);
  EXPECT_GT(hits, 40);
  EXPECT_LT(worst_dt, 1e-12);
}

TEST(PairTimeOfImpact, TouchingAndSeparatingStonesLeave) {
  Fixture f;
  vg::RigidBodyState a, b;
  b.position_world = Eigen::Vector3d(kAa + kAb, 0, 0);
  b.velocity_world = Eigen::Vector3d(0.1, 0, 0);
  b = vg::with_angular_velocity_world(f.setup_b.model, b, Eigen::Vector3d(20, 5, 3));
  const vg::PairTimeOfImpact toi =
      vg::pair_time_of_impact({f.lens_a, f.setup_a, a}, {f.lens_b, f.setup_b, b}, 0.0, 0.05);
  EXPECT_FALSE(toi.hit);
  EXPECT_EQ(toi.time_s, 0.05);
  EXPECT_GT(toi.contact.gap_m, 1e-3);
  // Approaching instead: the contact is now.
  b.velocity_world = Eigen::Vector3d(-0.1, 0, 0);
  const vg::PairTimeOfImpact now =
      vg::pair_time_of_impact({f.lens_a, f.setup_a, a}, {f.lens_b, f.setup_b, b}, 0.0, 0.05);
  EXPECT_TRUE(now.hit);
  EXPECT_EQ(now.time_s, 0.0);
}

TEST(PairTimeOfImpact, BadInputIsNamed) {
  Fixture f;
  vg::RigidBodyState a, b;
  b.position_world = Eigen::Vector3d(0.05, 0, 0);
  try {
    vg::pair_time_of_impact({f.lens_a, f.setup_a, a}, {f.lens_b, f.setup_b, b}, 1.0, 0.5);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "horizon_s");
  }
  vg::PairTimeOfImpactOptions bad;
  bad.max_steps = 0;
  EXPECT_THROW(
      vg::pair_time_of_impact({f.lens_a, f.setup_a, a}, {f.lens_b, f.setup_b, b}, 0.0, 1.0, bad),
      vg::InvalidArgument);
  b.velocity_world.x() = std::nan("");
  EXPECT_THROW(
      vg::pair_time_of_impact({f.lens_a, f.setup_a, a}, {f.lens_b, f.setup_b, b}, 0.0, 1.0),
      vg::InvalidArgument);
}
