// Time of first contact against independent references: the test's own closed-form flight and
// lens support, a dense scan for the first sign change and a bracketing root finder (TOMS 748),
// GJK for edges and corners; closed forms where the stone does not tumble.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdio>
#include <random>

#include "support/flight_reference.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/common/validation.h"

namespace vg = virtual_go;

namespace {

constexpr double kA = 0.011, kC = 0.0046, kG = 9.80665;

struct Fixture {
  vg::LensShape shape{2 * kA, 2 * kC};
  vg::LensGeometry lens{shape};
  vg::BoardGeometry board;
  vg::BoardDistance distance{lens, board};
  vg::MassProperties mp = vg::MassProperties::of_lens(shape, 2700.0);
  vg::MotionSetup rigid{vg::MotionModel(vg::MotionModelKind::rigid_body, mp),
                        Eigen::Vector3d(0, 0, -kG)};
  vg::MotionSetup constant{vg::MotionModel(vg::MotionModelKind::constant_omega, mp),
                           Eigen::Vector3d(0, 0, -kG)};
  double hx = 0.5 * board.size_x_m, hy = 0.5 * board.size_y_m, t = board.thickness_m;
  std::mt19937 rng{77};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};

  Eigen::Vector3d random_unit() {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  }

  // A state and the reference flight through it.
  struct Throw {
    vg::RigidBodyState state;
    vgtest::FlightReference flight;
  };
  Throw make_throw(const vg::MotionSetup& setup, const Eigen::Vector3d& x, const Eigen::Vector3d& v,
                   const vgtest::Quat& q, const Eigen::Vector3d& omega_world) const {
    Throw th{vg::RigidBodyState(), vgtest::FlightReference{kA, kC, x, v, setup.gravity_world, {}}};
    th.state.position_world = x;
    th.state.velocity_world = v;
    th.state.orientation = vgtest::to_eigen(q);
    th.state.angular_momentum_world =
        setup.model.angular_momentum_world(th.state.orientation, omega_world);
    th.flight.top =
        vgtest::AxisymmetricTop{mp.principal_moments_body().x(), mp.principal_moments_body().z(), q,
                                th.state.angular_momentum_world};
    if (setup.model.kind() == vg::MotionModelKind::constant_omega) {
      th.flight.constant_omega = true;
      th.flight.omega_world = omega_world;
    }
    return th;
  }
  Throw random_throw(const vg::MotionSetup& setup) {
    const Eigen::Vector3d x(0.1 * (2 * uniform(rng) - 1), 0.1 * (2 * uniform(rng) - 1),
                            0.02 + 0.08 * uniform(rng));
    // Horizontal drift small enough that the stone lands on the top face (|x|, |y| < 0.16 m).
    const Eigen::Vector3d v(0.05 * normal(rng), 0.05 * normal(rng), 2 * uniform(rng) - 1);
    const vgtest::Quat q = vgtest::axis_angle(M_PI * uniform(rng) * random_unit());
    return make_throw(setup, x, v, q, 60.0 * random_unit());
  }
};

// The gap of the reference lens above the top face z = 0 (the stone stays over the face).
double top_face_gap(const vgtest::FlightReference& f, double t) {
  const vgtest::LensReference ref = f.lens_at(t);
  return ref.x.z() - ref.reach(Eigen::Vector3d::UnitZ());
}

// First root of gap(t) on [0, t_max]: dense scan for the first sign change, then TOMS 748.
template <class Gap>
double reference_root(const Gap& gap, double t_max, double scan_dt, double* min_before = nullptr) {
  double lo = 0.0, g_lo = gap(0.0), lowest = g_lo;
  for (double hi = scan_dt; hi <= t_max; hi += scan_dt) {
    const double g_hi = gap(hi);
    if (g_hi <= 0.0) {
      std::uintmax_t iterations = 200;
      const auto bracket = boost::math::tools::toms748_solve(
          gap, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(52), iterations);
      if (min_before) *min_before = lowest;
      return 0.5 * (bracket.first + bracket.second);
    }
    lowest = std::min(lowest, g_hi);
    lo = hi;
    g_lo = g_hi;
  }
  return -1.0;
}

void random_throws_match_the_reference(Fixture& fx, const vg::MotionSetup& setup, int throws,
                                       const char* label) {
  double worst_dt = 0.0, worst_gap_at_hit = 0.0, lowest_before = 1.0;
  int total_steps = 0, max_steps = 0, total_polish = 0;
  for (int k = 0; k < throws; ++k) {
    const Fixture::Throw th = fx.random_throw(setup);
    const vg::TimeOfImpact toi =
        vg::board_time_of_impact(fx.distance, setup, th.state, 0.0, 0.0, 2.0);
    ASSERT_TRUE(toi.hit) << k;
    ASSERT_EQ(toi.contact.feature.kind, vg::BoardFeatureKind::top_face) << k;
    double min_before = 1.0;
    const double t_ref = reference_root([&](double t) { return top_face_gap(th.flight, t); }, 2.0,
                                        1e-5, &min_before);
    ASSERT_GT(t_ref, 0.0);
    worst_dt = std::max(worst_dt, std::abs(toi.time_s - t_ref));
    worst_gap_at_hit = std::max(worst_gap_at_hit, std::abs(top_face_gap(th.flight, toi.time_s)));
    lowest_before = std::min(lowest_before, min_before);
    // The witness is on the board's plane and the normal is the face's.
    EXPECT_NEAR(toi.contact.lens.point_world.z(), 0.0, 1e-15);
    EXPECT_EQ(toi.contact.lens.normal_world, Eigen::Vector3d::UnitZ());
    EXPECT_GT(toi.approach_speed_mps, 0.0);
    total_steps += toi.advancement_steps;
    total_polish += toi.polish_steps;
    max_steps = std::max(max_steps, toi.advancement_steps);
  }
  std::printf(
      "[ measured ] %s: %d throws, max |t - t_ref| %.3g s, max |gap(t)| %.3g m, "
      "advancement steps mean %.2f max %d, polish steps mean %.2f\n",
      label, throws, worst_dt, worst_gap_at_hit, double(total_steps) / throws, max_steps,
      double(total_polish) / throws);
  EXPECT_LT(worst_dt, 1e-12);          // the goal; measured ~1e-16 s
  EXPECT_LT(worst_gap_at_hit, 1e-15);  // the reference gap at the returned time
  EXPECT_GT(lowest_before, 0.0);       // the scan saw no contact before the root
}

TEST(TimeOfImpact, RandomThrowsMatchAnIndependentRoot) {
  Fixture fx;
  random_throws_match_the_reference(fx, fx.rigid, 200, "rigid_body");
}

TEST(TimeOfImpact, RandomThrowsMatchAnIndependentRootWithConstantOmega) {
  Fixture fx;
  random_throws_match_the_reference(fx, fx.constant, 50, "constant_omega");
}

TEST(TimeOfImpact, NeverAContactBeforeTheReturnedTime) {
  // Dense check of the reference gap on [0, t*] for tumbling throws, also with the stone
  // starting only micrometres above the board.
  Fixture fx;
  for (int k = 0; k < 50; ++k) {
    Fixture::Throw th = fx.random_throw(fx.rigid);
    const vgtest::LensReference start = th.flight.lens_at(0.0);
    const double lift = std::pow(10.0, -7.0 + 5.0 * fx.uniform(fx.rng));  // 0.1 um .. 1 cm
    th.state.position_world.z() += lift - top_face_gap(th.flight, 0.0);
    th.flight.x0 = th.state.position_world;
    (void)start;
    const vg::TimeOfImpact toi =
        vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0.0, 0.0, 2.0);
    ASSERT_TRUE(toi.hit);
    for (int i = 0; i <= 20000; ++i) {
      const double t = toi.time_s * i / 20000;
      ASSERT_GE(top_face_gap(th.flight, t), -1e-16) << k << " at " << t << " of " << toi.time_s;
    }
  }
}

TEST(TimeOfImpact, AStoneSpinningFlatOneMicrometreAboveTakesOneStep) {
  Fixture fx;
  const Fixture::Throw th =
      fx.make_throw(fx.rigid, Eigen::Vector3d(0.05, 0.02, kC + 1e-6), Eigen::Vector3d::Zero(),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d(0, 0, 100.0));
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 1);
  ASSERT_TRUE(toi.hit);
  EXPECT_EQ(toi.advancement_steps, 1);
  EXPECT_LE(toi.polish_steps, 1);
  EXPECT_NEAR(toi.time_s, std::sqrt(2e-6 / kG), 1e-16);
  std::printf("[ measured ] spinning flat 1 um above: %d advancement + %d polish steps\n",
              toi.advancement_steps, toi.polish_steps);
}

TEST(TimeOfImpact, FlatDropsLandAtTheFreeFallTimeInOneStep) {
  Fixture fx;
  for (double h : {0.05, 1.0}) {
    const Fixture::Throw th =
        fx.make_throw(fx.rigid, Eigen::Vector3d(0, 0, kC + h), Eigen::Vector3d::Zero(),
                      vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d::Zero());
    const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 2);
    ASSERT_TRUE(toi.hit);
    EXPECT_EQ(toi.advancement_steps, 1);
    EXPECT_NEAR(toi.time_s, std::sqrt(2 * h / kG), 1e-16);
  }
  // CONTACT.md's number: 5 cm fall in 100.981 ms.
  const Fixture::Throw th =
      fx.make_throw(fx.rigid, Eigen::Vector3d(0, 0, kC + 0.05), Eigen::Vector3d::Zero(),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d::Zero());
  EXPECT_NEAR(vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 2).time_s, 0.100981,
              5e-7);
}

TEST(TimeOfImpact, TumblingFromHighAbove) {
  Fixture fx;
  int max_steps = 0;
  double worst_dt = 0;
  for (int k = 0; k < 20; ++k) {
    const Fixture::Throw th = fx.make_throw(
        fx.rigid, Eigen::Vector3d(0, 0, 1.0), Eigen::Vector3d::Zero(),
        vgtest::axis_angle(M_PI * fx.uniform(fx.rng) * fx.random_unit()), 60.0 * fx.random_unit());
    const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 2);
    ASSERT_TRUE(toi.hit);
    const double t_ref =
        reference_root([&](double t) { return top_face_gap(th.flight, t); }, 2.0, 1e-5);
    worst_dt = std::max(worst_dt, std::abs(toi.time_s - t_ref));
    max_steps = std::max(max_steps, toi.advancement_steps);
  }
  std::printf(
      "[ measured ] tumbling 60 rad/s from 1 m: max %d advancement steps, max |dt| %.3g s\n",
      max_steps, worst_dt);
  EXPECT_LT(worst_dt, 1e-12);
  EXPECT_LT(max_steps, 40);
}

// Whether GJK (lens vs box, written in the test) proves the lens apart from the board.
bool gjk_apart(const Fixture& fx, const vgtest::LensReference& lens) {
  const vgtest::GjkResult r =
      vgtest::gjk_distance(lens, vgtest::BoxReference{fx.hx, fx.hy, -fx.t, 0.0}, 300, true);
  return !r.overlap && r.lower > 0.0;
}

// The first time GJK finds the lens touching the board (a scan at 0.1 ms), -1 if never before
// t_max. Only a coarse check: GJK converges slowly on smooth shapes near contact.
double gjk_contact_scan(const Fixture& fx, const vgtest::FlightReference& f, double t_max) {
  for (double t = 1e-4; t <= t_max; t += 1e-4) {
    if (!gjk_apart(fx, f.lens_at(t))) return t;
  }
  return -1.0;
}

// The lens's signed distance to a point: max over unit n of n . (x - p) - reach(n), by a
// zooming grid over the sphere of directions (written in the test).
double point_gap_by_scan(const vgtest::LensReference& ref, const Eigen::Vector3d& p) {
  auto f = [&](double theta, double phi) {
    const Eigen::Vector3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                            std::cos(theta));
    return n.dot(ref.x - p) - ref.reach(n);
  };
  const Eigen::Vector3d w = (ref.x - p).normalized();  // start around the centre's direction
  double th0 = std::acos(std::clamp(w.z(), -1.0, 1.0)), ph0 = std::atan2(w.y(), w.x());
  double dth = 0.5 * M_PI, dph = M_PI, best = -1e9;
  for (int zoom = 0; zoom < 16; ++zoom) {
    double b_th = th0, b_ph = ph0;
    for (int i = -16; i <= 16; ++i) {
      for (int j = -16; j <= 16; ++j) {
        const double th = th0 + dth * i / 16, ph = ph0 + dph * j / 16, v = f(th, ph);
        if (v > best) {
          best = v;
          b_th = th;
          b_ph = ph;
        }
      }
    }
    th0 = b_th;
    ph0 = b_ph;
    dth *= 0.2;
    dph *= 0.2;
  }
  return best;
}

TEST(TimeOfImpact, EdgeHitsMatchTheLineGapRoot) {
  // Stones falling tilted over the +x top edge, some spinning. Reference: the root of the
  // test's own signed lens-line distance (direction scan + Brent); GJK checks that nothing of
  // the board was touched before.
  Fixture fx;
  const Eigen::Vector3d edge_point(fx.hx, 0.0, 0.0), edge_dir = Eigen::Vector3d::UnitY();
  double worst = 0;
  int edges = 0;
  for (int k = 0; k < 12; ++k) {
    const double tilt = 0.3 + 0.9 * fx.uniform(fx.rng);
    const Fixture::Throw th = fx.make_throw(
        fx.rigid, Eigen::Vector3d(fx.hx + 0.002 + 0.004 * fx.uniform(fx.rng), 0.05, 0.02),
        Eigen::Vector3d(0.0, 0.1 * fx.normal(fx.rng), -0.3),
        vgtest::axis_angle(Eigen::Vector3d(0, tilt, 0)), 5.0 * fx.random_unit());
    const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 1);
    ASSERT_TRUE(toi.hit);
    if (toi.contact.feature != vg::BoardFeature{vg::BoardFeatureKind::top_edge, 0}) continue;
    ++edges;
    const double t_ref = reference_root(
        [&](double t) {
          return vgtest::line_gap_by_scan(th.flight.lens_at(t), edge_point, edge_dir);
        },
        1.0, 2e-3);
    worst = std::max(worst, std::abs(toi.time_s - t_ref));
    EXPECT_TRUE(gjk_apart(fx, th.flight.lens_at(t_ref - 1e-6)));
    EXPECT_EQ(gjk_contact_scan(fx, th.flight, t_ref - 1e-4), -1.0);
    // The normal is perpendicular to the edge and points up and away from the board.
    EXPECT_NEAR(toi.contact.lens.normal_world.y(), 0.0, 1e-12);
    EXPECT_GT(toi.contact.lens.normal_world.x(), 0.0);
  }
  std::printf("[ measured ] edge hits: max |t - t_ref| %.3g s (%d of 12 on the edge)\n", worst,
              edges);
  EXPECT_LT(worst, 1e-12);
  EXPECT_GE(edges, 6);
}

TEST(TimeOfImpact, CornerHitsMatchThePointGapRoot) {
  Fixture fx;
  const Eigen::Vector3d corner(fx.hx, fx.hy, 0.0);
  double worst = 0;
  int corners = 0;
  for (int k = 0; k < 8; ++k) {
    // Beyond the corner, axis tilted towards the board (below beta = 45 deg: the bottom cap's
    // lowest point lies towards the corner).
    const double tilt = 0.2 + 0.5 * fx.uniform(fx.rng);
    const Fixture::Throw th = fx.make_throw(
        fx.rigid, Eigen::Vector3d(fx.hx + 0.004, fx.hy + 0.004, 0.02), Eigen::Vector3d(0, 0, -0.3),
        vgtest::axis_angle(tilt * Eigen::Vector3d(1, -1, 0).normalized()), 3.0 * fx.random_unit());
    const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 1);
    ASSERT_TRUE(toi.hit);
    if (toi.contact.feature != vg::BoardFeature{vg::BoardFeatureKind::top_corner, 0}) continue;
    ++corners;
    const double t_ref = reference_root(
        [&](double t) { return point_gap_by_scan(th.flight.lens_at(t), corner); }, 1.0, 2e-3);
    worst = std::max(worst, std::abs(toi.time_s - t_ref));
    EXPECT_EQ(gjk_contact_scan(fx, th.flight, t_ref - 1e-4), -1.0);
  }
  std::printf("[ measured ] corner hits: max |t - t_ref| %.3g s (%d of 8 on the corner)\n", worst,
              corners);
  EXPECT_LT(worst, 1e-12);
  EXPECT_GE(corners, 4);
}

TEST(TimeOfImpact, ARimOnACornerGetsTheApproachNormal) {
  // Standing on its rim in the board's diagonal plane (axis horizontal, across the diagonal),
  // beyond the corner, falling so that the rim point 45 deg below the centre comes down on the
  // corner: the contact normal is (d + e_z) / sqrt 2, d the diagonal, inside the corner's
  // normal cone, so nothing else of the board is nearer. At the contact the corner-to-rim
  // direction is a round-off-sized difference; the normal must be its limit.
  Fixture fx;
  const Eigen::Vector3d diagonal = Eigen::Vector3d(1, 1, 0).normalized();
  const Eigen::Vector3d corner(fx.hx, fx.hy, 0.0);
  const Eigen::Vector3d x = corner + (kA / std::sqrt(2.0)) * diagonal +
                            (kA / std::sqrt(2.0) + 0.01) * Eigen::Vector3d::UnitZ();
  const vgtest::Quat q = vgtest::axis_angle(-0.5 * M_PI * diagonal);  // e_z -> (-1, 1, 0)/sqrt 2
  const Fixture::Throw th =
      fx.make_throw(fx.rigid, x, Eigen::Vector3d(0, 0, -0.3), q, Eigen::Vector3d::Zero());
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 1);
  ASSERT_TRUE(toi.hit);
  ASSERT_EQ(toi.contact.feature, (vg::BoardFeature{vg::BoardFeatureKind::top_corner, 0}));
  ASSERT_EQ(toi.contact.lens.part, vg::LensPart::rim);
  const Eigen::Vector3d expected = (diagonal + Eigen::Vector3d::UnitZ()).normalized();
  EXPECT_LT((toi.contact.lens.normal_world - expected).norm(), 1e-12)
      << toi.contact.lens.normal_world.transpose();
  // The fall to the contact: 1 cm at 0.3 m/s under gravity.
  EXPECT_NEAR(toi.time_s, (-0.3 + std::sqrt(0.09 + 2 * kG * 0.01)) / kG, 1e-15);
}

TEST(TimeOfImpact, SideFaceWithoutGravityIsClosedForm) {
  Fixture fx;
  vg::MotionSetup weightless{fx.rigid.model, Eigen::Vector3d::Zero()};
  const double x0 = fx.hx + 0.1, v = 0.7;
  const Fixture::Throw th =
      fx.make_throw(weightless, Eigen::Vector3d(x0, 0.03, -0.05), Eigen::Vector3d(-v, 0, 0),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d(0, 0, 80.0));  // spins on its axis
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, weightless, th.state, 0, 0, 1);
  ASSERT_TRUE(toi.hit);
  EXPECT_EQ(toi.contact.feature, (vg::BoardFeature{vg::BoardFeatureKind::side_face, 0}));
  EXPECT_EQ(toi.contact.lens.part, vg::LensPart::rim);
  EXPECT_NEAR(toi.time_s, (x0 - kA - fx.hx) / v, 1e-16);
  EXPECT_EQ(toi.advancement_steps, 1);
  // Gravity zero, moving down onto the face: (z0 - c) / |v_z|.
  const Fixture::Throw down =
      fx.make_throw(weightless, Eigen::Vector3d(0, 0, 0.03), Eigen::Vector3d(0, 0, -0.4),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d::Zero());
  EXPECT_NEAR(vg::board_time_of_impact(fx.distance, weightless, down.state, 0, 0, 1).time_s,
              (0.03 - kC) / 0.4, 1e-16);
}

TEST(TimeOfImpact, TheTableBesideTheBoard) {
  Fixture fx;
  const double z0 = 0.02;
  const Fixture::Throw th =
      fx.make_throw(fx.rigid, Eigen::Vector3d(fx.hx + 0.05, 0.0, z0), Eigen::Vector3d::Zero(),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d::Zero());
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 2);
  ASSERT_TRUE(toi.hit);
  EXPECT_TRUE(toi.contact.on_table());
  EXPECT_NEAR(toi.time_s, std::sqrt(2 * (z0 + fx.t - kC) / kG), 1e-16);
  // Thrown sideways off the board's top it passes the edge and lands on the table.
  const Fixture::Throw off = fx.make_throw(
      fx.rigid, Eigen::Vector3d(fx.hx - 0.02, 0.0, 0.03), Eigen::Vector3d(1.0, 0, 0.5),
      vgtest::axis_angle(Eigen::Vector3d(0.3, 0.2, 0)), 20.0 * fx.random_unit());
  const vg::TimeOfImpact landing =
      vg::board_time_of_impact(fx.distance, fx.rigid, off.state, 0, 0, 2);
  ASSERT_TRUE(landing.hit);
  EXPECT_TRUE(landing.contact.on_table());
  const double t_ref = reference_root(
      [&](double t) {
        const vgtest::LensReference ref = off.flight.lens_at(t);
        return ref.x.z() + fx.t - ref.reach(Eigen::Vector3d::UnitZ());
      },
      2.0, 1e-5);
  EXPECT_NEAR(landing.time_s, t_ref, 1e-12);
  EXPECT_EQ(gjk_contact_scan(fx, off.flight, t_ref), -1.0);  // GJK: never touches the board
  std::printf("[ measured ] off the board onto the table: %d advancement steps\n",
              landing.advancement_steps);
}

TEST(TimeOfImpact, AStoneThatJustBouncedLeavesAndLandsAgain) {
  Fixture fx;
  const double v = 0.5;
  const Fixture::Throw th =
      fx.make_throw(fx.rigid, Eigen::Vector3d(0, 0, kC), Eigen::Vector3d(0, 0, v),
                    vgtest::Quat(1, 0, 0, 0), Eigen::Vector3d(0, 0, 30.0));
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0, 1);
  ASSERT_TRUE(toi.hit);
  EXPECT_NEAR(toi.time_s, 2 * v / kG, 1e-16);
  EXPECT_LE(toi.advancement_steps, 2);
  // A search started later on the same flight (anchor at 0) finds the same contact.
  const vg::TimeOfImpact later =
      vg::board_time_of_impact(fx.distance, fx.rigid, th.state, 0, 0.05, 1);
  EXPECT_NEAR(later.time_s, 2 * v / kG, 1e-16);
}

TEST(TimeOfImpact, NoContactBeforeTheHorizon) {
  Fixture fx;
  const Fixture::Throw up =
      fx.make_throw(fx.rigid, Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0, 0, 1.0),
                    vgtest::axis_angle(Eigen::Vector3d(0.5, 0, 0)), 40.0 * fx.random_unit());
  const vg::TimeOfImpact toi = vg::board_time_of_impact(fx.distance, fx.rigid, up.state, 0, 0, 0.1);
  EXPECT_FALSE(toi.hit);
  EXPECT_FALSE(toi.exhausted);
  EXPECT_EQ(toi.time_s, 0.1);
  EXPECT_NEAR((toi.state.position_world - up.flight.position_at(0.1)).norm(), 0.0, 1e-16);
  EXPECT_GT(toi.contact.lens.gap_m, 0.0);
  // Weightless, drifting away from the board: one step proves it never comes back.
  vg::MotionSetup weightless{fx.rigid.model, Eigen::Vector3d::Zero()};
  const Fixture::Throw away =
      fx.make_throw(weightless, Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0.1, 0, 0.2),
                    vgtest::axis_angle(Eigen::Vector3d(0.5, 0, 0)), 40.0 * fx.random_unit());
  const vg::TimeOfImpact never =
      vg::board_time_of_impact(fx.distance, weightless, away.state, 0, 0, 1e6);
  EXPECT_FALSE(never.hit);
  EXPECT_EQ(never.advancement_steps, 0);
}

TEST(TimeOfImpact, BadTimesAreRefusedByName) {
  Fixture fx;
  vg::RigidBodyState s;
  s.position_world.z() = 0.1;
  const std::string what = vgtest::what_of<vg::InvalidArgument>(
      [&] { vg::board_time_of_impact(fx.distance, fx.rigid, s, 0, 1.0, 0.5); });
  EXPECT_TRUE(vgtest::contains(what, "horizon")) << what;
  EXPECT_TRUE(vgtest::contains(vgtest::what_of<vg::InvalidArgument>([&] {
                                 vg::board_time_of_impact(fx.distance, fx.rigid, s, NAN, 0, 1);
                               }),
                               "anchor time"));
  vg::TimeOfImpactOptions options;
  options.touch_tolerance_m = -1.0;
  EXPECT_TRUE(vgtest::contains(vgtest::what_of<vg::InvalidArgument>([&] {
                                 vg::board_time_of_impact(fx.distance, fx.rigid, s, 0, 0, 1,
                                                          options);
                               }),
                               "touch_tolerance_m"));
  s.orientation.coeffs().setZero();  // the anchor state itself is checked
  EXPECT_THROW(vg::board_time_of_impact(fx.distance, fx.rigid, s, 0, 0, 1), vg::InvalidArgument);
}

}  // namespace
