// The article's constant_omega model: world angular velocity constant, so
// q(t) = exp(t omega) q0 (docs/physics.md). exact and splitting take that rotation in closed form;
// euler and rk4 converge to it. With omega fixed, the article's euler step
// q <- normalise((1 + dt omega / 2) q) is an exact turn about the right axis by
// 2 atan(|omega| dt / 2) instead of |omega| dt, so here it is second order with a known error.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/physics_reference.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vgtest::Quat;

namespace {

const Eigen::Vector3d kOmegaWorld(3.0, -4.0, 12.0);  // |omega| = 13 rad/s

vg::MotionSetup article_setup() {
  return {vg::MotionModel(vg::MotionModelKind::constant_omega,
                          vg::make_stone(vg::StoneSpec{}).mass_properties),
          vg::kStandardGravity};
}

vg::RigidBodyState start(const vg::MotionSetup& setup) {
  vg::RigidBodyState s;
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(1.0, 0.2, -0.4)));
  return vg::with_angular_velocity_world(setup.model, s, kOmegaWorld);
}

Quat reference(const vg::RigidBodyState& s0, double t) {
  return vgtest::qmul(vgtest::axis_angle(t * kOmegaWorld), vgtest::from_eigen(s0.orientation));
}

double error_at(const std::string& name, double dt, double t_end) {
  const vg::MotionSetup setup = article_setup();
  vg::RigidBodyState s = start(setup);
  const vg::RigidBodyState s0 = s;
  auto integrator = vg::make_integrator(name, setup);
  vg::FlightCache cache;  // the stone's own, carried from step to step
  const int n = static_cast<int>(std::lround(t_end / dt));
  for (int i = 0; i < n; ++i) {
    integrator->advance(s, dt, cache);
    // The model's defining property: world omega never changes.
    EXPECT_TRUE(
        vg::RigidBody(setup.model, s).angular_velocity_world().isApprox(kOmegaWorld, 1e-14));
  }
  return vgtest::angle_between(reference(s0, t_end), vgtest::from_eigen(s.orientation));
}

}  // namespace

TEST(ConstantOmega, ClosedFormMotionIsTheWorldRotation) {
  const vg::MotionSetup setup = article_setup();
  const vg::RigidBodyState s0 = start(setup);
  const vg::ExactMotion motion(setup, s0);
  for (double t : {0.0, 0.01, 0.37, 1.0, 10.0}) {
    EXPECT_LT(
        vgtest::angle_between(reference(s0, t), vgtest::from_eigen(motion.state_at(t).orientation)),
        1e-14 * (1 + 13 * t))
        << t;
  }
}

TEST(ConstantOmega, ExactAndSplittingFollowItForAnyStep) {
  for (const std::string& name : std::vector<std::string>{"exact", "splitting"}) {
    for (double dt : {0.5, 0.1, 1e-3}) {
      EXPECT_LT(error_at(name, dt, 2.0), 1e-12) << name << " dt " << dt;
    }
  }
}

TEST(ConstantOmega, ArticleEulerLagsByTheKnownAngle) {
  const double w = kOmegaWorld.norm();
  std::vector<double> dts, errors;
  for (int steps = 100; steps <= 800; steps *= 2) {
    const double dt = 1.0 / steps;
    const double predicted = steps * (w * dt - 2 * std::atan(0.5 * w * dt));  // ~ w^3 dt^2 / 12
    dts.push_back(dt);
    errors.push_back(error_at("euler", dt, 1.0));
    EXPECT_NEAR(errors.back(), predicted, 1e-12 + 1e-9 * predicted) << "dt " << dt;
  }
  const double order = vgtest::fitted_order(dts, errors);
  std::printf("constant_omega euler error %.3e .. %.3e rad, fitted order %.3f\n", errors.front(),
              errors.back(), order);
  EXPECT_NEAR(order, 2.0, 0.05);
}

TEST(ConstantOmega, Rk4ConvergesAtFourthOrder) {
  std::vector<double> dts, errors;
  for (int steps = 20; steps <= 160; steps *= 2) {
    dts.push_back(1.0 / steps);
    errors.push_back(error_at("rk4", dts.back(), 1.0));
  }
  const double order = vgtest::fitted_order(dts, errors);
  std::printf("constant_omega rk4 error %.3e .. %.3e rad, fitted order %.3f\n", errors.front(),
              errors.back(), order);
  EXPECT_NEAR(order, 4.0, 0.15);
}
