// The DOP853 stepper (dop853.h) against closed forms: its measured orders of accuracy (8 for a
// step, 7 for the dense output, so local errors of orders 9 and 8), exactness on polynomials it
// must integrate exactly, and the error estimate's controller on a problem with a known solution.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_go/contact/dop853.h"

namespace dop = virtual_go::dop853;
using V2 = dop::Vector<2>;

namespace {

// y1' = y1^2 (y1 = 1 / (1 - t)), y2' = -y2 cos t (y2 = exp(-sin t)): nonlinear and
// non-autonomous, both with closed forms.
struct Problem {
  void operator()(double t, const V2& y, V2& dydt) const {
    dydt[0] = y[0] * y[0];
    dydt[1] = -y[1] * std::cos(t);
  }
  static V2 exact(double t) { return V2(1.0 / (1.0 - t), std::exp(-std::sin(t))); }
};

struct OneStep {
  double step_error, dense_error;
};

// One step of size h from the exact state at t0, compared with the closed form at its end and
// (through the dense output) at its middle.
OneStep one_step(double t0, double h) {
  Problem f;
  dop::Stages<2> k;
  const V2 y0 = Problem::exact(t0);
  f(t0, y0, k[0]);
  V2 y1, e5, e3;
  dop::trial_step<2>(f, t0, h, y0, k, y1, e5, e3);
  f(t0 + h, y1, k[12]);
  std::array<V2, 4> dense;
  dop::dense_coefficients<2>(f, t0, h, y0, k, dense);
  const V2 mid = dop::interpolate<2>(0.5, h, y0, y1, k[0], k[12], dense);
  return {(y1 - Problem::exact(t0 + h)).cwiseAbs().maxCoeff(),
          (mid - Problem::exact(t0 + 0.5 * h)).cwiseAbs().maxCoeff()};
}

}  // namespace

TEST(Dop853, MeasuredLocalOrdersAreNineForTheStepAndEightForTheDenseOutput) {
  const OneStep coarse = one_step(0.1, 0.08), fine = one_step(0.1, 0.04);
  const double step_order = std::log2(coarse.step_error / fine.step_error);
  const double dense_order = std::log2(coarse.dense_error / fine.dense_error);
  std::cout << "[ measured ] local order of a step " << step_order << ", of the dense output "
            << dense_order << "\n";
  EXPECT_NEAR(step_order, 9.0, 0.6);
  EXPECT_NEAR(dense_order, 8.0, 0.6);
}

TEST(Dop853, DenseOutputMatchesTheStepsEndsAndIsExactOnAPolynomial) {
  // y' = 7 t^6: y = t^7 is within the method's order: every stage and the interpolant are exact.
  auto f = [](double t, const dop::Vector<1>& /*y*/, dop::Vector<1>& dydt) {
    dydt[0] = 7.0 * std::pow(t, 6);
  };
  dop::Stages<1> k;
  const double t0 = 0.5, h = 0.75;
  const dop::Vector<1> y0(std::pow(t0, 7));
  f(t0, y0, k[0]);
  dop::Vector<1> y1, e5, e3;
  dop::trial_step<1>(f, t0, h, y0, k, y1, e5, e3);
  f(t0 + h, y1, k[12]);
  EXPECT_NEAR(y1[0], std::pow(t0 + h, 7), 1e-14 * std::pow(t0 + h, 7));
  std::array<dop::Vector<1>, 4> dense;
  dop::dense_coefficients<1>(f, t0, h, y0, k, dense);
  for (double theta : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const double t = t0 + theta * h;
    const double y = dop::interpolate<1>(theta, h, y0, y1, k[0], k[12], dense)[0];
    EXPECT_NEAR(y, std::pow(t, 7), 1e-14 * std::pow(t0 + h, 7)) << theta;
  }
  EXPECT_EQ(dop::interpolate<1>(0.0, h, y0, y1, k[0], k[12], dense)[0], y0[0]);
}

TEST(Dop853, ControlledStepsReachTheToleranceOnAKnownSolution) {
  // Adaptive stepping with the error norm and controller, to t = 0.9 (y1 = 10, growing fast).
  Problem f;
  const double rtol = 1e-12, atol = 1e-14, t_end = 0.9;
  double t = 0.0, h = 1e-3;
  V2 y = Problem::exact(0.0), rates;
  f(t, y, rates);
  int steps = 0, rejected = 0;
  while (t < t_end && steps < 10000) {
    h = std::min(h, t_end - t);
    dop::Stages<2> k;
    k[0] = rates;
    V2 y1, e5, e3;
    dop::trial_step<2>(f, t, h, y, k, y1, e5, e3);
    const V2 scale = (atol + rtol * y.cwiseAbs().cwiseMax(y1.cwiseAbs()).array()).matrix();
    const double error = dop::error_norm<2>(h, e5, e3, scale);
    if (error > 1.0) {
      h = dop::next_step_size(h, error, true);
      ++rejected;
      continue;
    }
    t += h;
    y = y1;
    f(t, y, rates);
    h = dop::next_step_size(h, error, false);
    ++steps;
  }
  const V2 exact = Problem::exact(t_end);
  const double relative = ((y - exact).array() / exact.array()).abs().maxCoeff();
  std::cout << "[ measured ] " << steps << " steps, " << rejected << " rejected, relative error "
            << relative << " at t = 0.9\n";
  EXPECT_EQ(t, t_end);
  EXPECT_LT(relative, 1e-10);  // a per-step tolerance of 1e-12 over a solution growing tenfold
  EXPECT_LT(steps, 200);
}
