// Long runs: 10^7 exact steps of the tumble, 10^6 splitting steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include "support/stress_cases.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"

namespace {

using namespace stress;

TEST(StressLong, TenMillionExactStepsOfTheTumbleStayOnTheClosedForm) {
  const Case c = tumble();
  const auto exact = vg::make_integrator("exact", c.setup);
  vg::FlightCache cache;
  vg::RigidBodyState s = c.initial;
  const double dt = 1.0 / 60.0;
  const std::int64_t n = 10'000'000;
  double max_norm_error = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    exact->advance(s, dt, cache);
    max_norm_error = std::max(max_norm_error, std::abs(s.orientation.norm() - 1.0));
  }
  EXPECT_LT(max_norm_error, 1e-12);
  const double l_drift = (s.angular_momentum_world - c.initial.angular_momentum_world).norm() /
                         c.initial.angular_momentum_world.norm();
  EXPECT_LT(l_drift, 1e-12);
  // t = n dt with the double dt the integrator was given, ~1.67e5 s.
  const long double t = static_cast<long double>(n) * static_cast<long double>(dt);
  const long double error =
      orientation_error_l(closed_form_orientation(slate33(), c.initial, t), s.orientation);
  EXPECT_LT(error, 1e-9L) << "after " << n << " steps, t = " << static_cast<double>(t) << " s";
  // The core's own closed form at the same t, for the record (shares double round-off).
  const vg::ExactMotion motion(c.setup, c.initial);
  const double self_error = vg::orientation_error(
      motion.state_at(static_cast<double>(n) * dt).orientation, s.orientation);
  EXPECT_LT(self_error, 1e-9);
  RecordProperty("orientation_error_vs_long_double", std::to_string(static_cast<double>(error)));
  RecordProperty("orientation_error_vs_state_at", std::to_string(self_error));
  std::printf(
      "exact 1e7 steps: | |q| - 1 | max %.3g, L drift %.3g, error vs long double %.3g rad, "
      "vs state_at %.3g rad\n",
      max_norm_error, l_drift, static_cast<double>(error), self_error);
}

TEST(StressLong, SplittingEnergyErrorStaysBoundedOverAMillionSteps) {
  const Case c = tumble();
  const auto splitting = vg::make_integrator("splitting", c.setup);
  vg::FlightCache cache;
  vg::RigidBodyState s = c.initial;
  const vg::MotionModel& model = c.setup.model;
  // Rotational energy: the translation is exact in closed form, the rotation is what is split.
  const double e0 = vg::RigidBody(model, s).rotational_kinetic_energy();
  const int n = 1'000'000;
  double max_first = 0.0, max_second = 0.0, max_l_drift = 0.0;
  for (int k = 1; k <= n; ++k) {
    splitting->advance(s, 1.0 / 60.0, cache);
    const double e = std::abs(vg::RigidBody(model, s).rotational_kinetic_energy() - e0) / e0;
    (k <= n / 2 ? max_first : max_second) = std::max(k <= n / 2 ? max_first : max_second, e);
    max_l_drift =
        std::max(max_l_drift, (s.angular_momentum_world - c.initial.angular_momentum_world).norm() /
                                  c.initial.angular_momentum_world.norm());
  }
  EXPECT_GT(max_first, 0.0);  // it is an approximation at this step: the bound is not vacuous
  EXPECT_LE(max_second, 1.10 * max_first)
      << "energy error drifts: first half " << max_first << ", second half " << max_second;
  EXPECT_LT(max_first, 0.1);
  EXPECT_LT(max_l_drift, 1e-12);
  EXPECT_TRUE(unit_and_finite(s));
  std::printf(
      "splitting 1e6 steps: max rel. energy error first half %.4g, second half %.4g, "
      "L drift %.3g\n",
      max_first, max_second, max_l_drift);
}

}  // namespace
