// The conservative-advancement bounds against the true gap along a fixed direction, computed on
// the test's own closed-form flight (parabola + torque-free axisymmetric top) and the test's own
// lens support: the bound never exceeds the gap, the safe step never passes its first root, and
// for a stone whose axis does not move the step lands exactly on the root.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/flight_reference.h"
#include "support/physics_reference.h"
#include "virtual_go/contact/flight_gap_bound.h"
#include "virtual_go/body/mass_properties.h"
#include "virtual_go/geometry/lens_shape.h"

namespace vg = virtual_go;

namespace {

constexpr double kA = 0.011, kC = 0.0046, kG = 9.80665;

struct Flight : vgtest::FlightReference {
  Flight() : vgtest::FlightReference{kA, kC, {}, {}, {}, {}} {}
  double gap(double t, const Eigen::Vector3d& n, double support) const {
    const vgtest::LensReference ref = lens_at(t);
    return n.dot(ref.x) - ref.reach(n) - support;
  }
};

struct Fixture {
  vg::LensShape shape{2 * kA, 2 * kC};
  vg::LensGeometry lens{shape};
  vg::MassProperties mp = vg::MassProperties::of_lens(shape, 2700.0);
  std::mt19937 rng{2024};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};

  Eigen::Vector3d random_unit() {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  }
  Flight random_flight(double spin) {
    Flight f;
    f.x0 = Eigen::Vector3d(0.01 * normal(rng), 0.01 * normal(rng), 0.05 * uniform(rng));
    f.v0 = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    f.g = Eigen::Vector3d(0, 0, -kG);
    const Eigen::Vector3d axis = random_unit();
    f.top.q0 = vgtest::axis_angle(M_PI * uniform(rng) * axis);
    f.top.i1 = mp.principal_moments_body().x();
    f.top.i3 = mp.principal_moments_body().z();
    // omega ~ spin rad/s in a random direction: L = R I R^T omega.
    const Eigen::Vector3d omega_world = spin * random_unit();
    const Eigen::Vector3d w_body = vgtest::rotate(vgtest::qconj(f.top.q0), omega_world);
    f.top.l_world = vgtest::rotate(
        f.top.q0,
        Eigen::Vector3d(f.top.i1 * w_body.x(), f.top.i1 * w_body.y(), f.top.i3 * w_body.z()));
    return f;
  }
  vg::FlightGapBound bound(const Flight& f, const Eigen::Vector3d& n, double support) const {
    vg::LensPose pose;
    pose.center_world = f.x0;
    pose.axis_world = vgtest::rotate(f.top.q0, Eigen::Vector3d::UnitZ());
    return vg::FlightGapBound(lens, pose, f.v0, f.top.l_world / f.top.i1, f.g, n, support);
  }
};

TEST(FlightGapBound, NeverAboveTheGapAndNeverPastItsRoot) {
  Fixture fx;
  int violations = 0, step_violations = 0, roots = 0;
  double tightest = 1e9;
  for (int k = 0; k < 300; ++k) {
    const Flight f = fx.random_flight(60.0 * fx.uniform(fx.rng) + 1.0);
    const Eigen::Vector3d n = fx.random_unit();
    // An obstacle 0.01 um .. 3 cm away along n.
    const double gap0 = std::pow(10.0, -8.0 + 6.5 * fx.uniform(fx.rng));
    const vgtest::LensReference start = f.lens_at(0.0);
    const double support = n.dot(start.x) - start.reach(n) - gap0;
    const vg::FlightGapBound bound = fx.bound(f, n, support);
    EXPECT_NEAR(bound.gap(), gap0, 1e-16);
    double first_root = std::numeric_limits<double>::infinity();
    constexpr int kSamples = 4000;
    constexpr double kSpan = 0.4;
    for (int i = 1; i <= kSamples; ++i) {
      const double tau = kSpan * i / kSamples;
      const double g = f.gap(tau, n, support);
      if (bound.lower_bound(tau) > g + 1e-16) ++violations;
      if (g <= 0.0 && !std::isfinite(first_root)) first_root = tau;
      tightest = std::min(tightest, g - bound.lower_bound(tau));
    }
    const double step = bound.safe_step();
    if (std::isfinite(first_root)) {
      ++roots;
      if (step >= first_root) ++step_violations;
    }
    // On the safe step itself and a dense grid before it the true gap is positive.
    for (int i = 0; i <= 200; ++i) {
      const double tau = std::min(step, kSpan) * i / 200;
      if (f.gap(tau, n, support) < -1e-16) ++step_violations;
    }
  }
  EXPECT_EQ(violations, 0);
  EXPECT_EQ(step_violations, 0);
  EXPECT_GT(roots, 100);
}

TEST(FlightGapBound, RateIsTheGapsDerivative) {
  Fixture fx;
  for (int k = 0; k < 100; ++k) {
    const Flight f = fx.random_flight(60.0);
    const Eigen::Vector3d n = fx.random_unit();
    const vg::FlightGapBound bound = fx.bound(f, n, -1.0);
    const double h = 1e-6;
    const double numeric = (f.gap(h, n, -1.0) - f.gap(-h, n, -1.0)) / (2 * h);
    EXPECT_NEAR(bound.rate(), numeric, 1e-7 * (1 + std::abs(numeric)));
  }
}

TEST(FlightGapBound, AnAxisAtRestLandsExactlyOnTheRoot) {
  // Spinning about its own axis (or not at all) the reach along n is constant: every bound is
  // the exact parabola, so one step reaches the contact: sqrt(2 h / g) for a flat drop from h.
  Fixture fx;
  for (double h : {1e-6, 1e-3, 0.05, 1.0}) {
    Flight f;
    f.x0 = Eigen::Vector3d(0.0, 0.0, kC + h);
    f.v0 = Eigen::Vector3d::Zero();
    f.g = Eigen::Vector3d(0, 0, -kG);
    f.top.q0 = vgtest::Quat(1, 0, 0, 0);
    f.top.i1 = fx.mp.principal_moments_body().x();
    f.top.i3 = fx.mp.principal_moments_body().z();
    f.top.l_world = Eigen::Vector3d(0, 0, f.top.i3 * 300.0);  // 300 rad/s about the axis
    const vg::FlightGapBound bound = fx.bound(f, Eigen::Vector3d::UnitZ(), 0.0);
    // Tolerance: the round-off of the height (ulp(z) ~ 1e-18 m) over the landing speed.
    const double fall = std::sqrt(2 * h / kG);
    EXPECT_NEAR(bound.safe_step(), fall, 1e-15 * fall + 4e-18 / (kG * fall)) << h;
  }
}

TEST(FlightGapBound, ATouchingStoneMayLeaveButNotApproach) {
  Fixture fx;
  Flight f = fx.random_flight(30.0);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const vgtest::LensReference start = f.lens_at(0.0);
  const double support = n.dot(start.x) - start.reach(n);  // gap 0 now
  f.v0.z() = 2.0;                                          // rising fast: separates
  vg::FlightGapBound leaving = fx.bound(f, n, support);
  ASSERT_GT(leaving.rate(), 0.0);
  EXPECT_EQ(leaving.safe_step(false), 0.0);  // without the touching rule no step is safe
  const double step = leaving.safe_step(true);
  EXPECT_GT(step, 0.1);  // about 2 v / g minus the rotation's allowance
  for (int i = 1; i <= 1000; ++i) EXPECT_GE(f.gap(step * i / 1000, n, support), -1e-16);
  f.v0.z() = -2.0;  // approaching: no step
  EXPECT_EQ(fx.bound(f, n, support).safe_step(true), 0.0);
}

TEST(FlightGapBound, ARisingStoneATinyGapAboveReturnsAfterTwoVOverG) {
  // Flat, not rotating, a round-off-sized gap above the plane and rising at v: it comes back to
  // the same height after exactly 2 v / g. The root formula must not cancel here.
  Fixture fx;
  for (double v : {1.0, 0.0619, 1e-3}) {
    for (double gap0 : {0.0, 3.5e-18, 1e-15, 1e-12}) {
      Flight f;
      f.x0 = Eigen::Vector3d(0.0, 0.0, kC + gap0);
      f.v0 = Eigen::Vector3d(0.0, 0.0, v);
      f.g = Eigen::Vector3d(0, 0, -kG);
      f.top = vgtest::AxisymmetricTop{fx.mp.principal_moments_body().x(),
                                      fx.mp.principal_moments_body().z(), vgtest::Quat(1, 0, 0, 0),
                                      Eigen::Vector3d::Zero()};
      const vg::FlightGapBound bound = fx.bound(f, Eigen::Vector3d::UnitZ(), 0.0);
      const double step = bound.safe_step(true);
      // The exact root: gap0 + v t - g t^2 / 2 = 0.
      const double root = (v + std::sqrt(v * v + 2 * kG * bound.gap())) / kG;
      EXPECT_NEAR(step, root, 1e-15 * root) << v << " " << gap0;
      EXPECT_GE(f.gap(step, Eigen::Vector3d::UnitZ(), 0.0), -1e-17) << v << " " << gap0;
    }
  }
}

}  // namespace
