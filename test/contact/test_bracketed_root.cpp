// rising_root against a bisection written here (to adjacent doubles) on functions with known
// crossings: the answer is always on the event's side (f >= 0), within the tolerance of the
// crossing, with a bracket the bisection confirms; an exact slope needs a few samples, a poor or
// missing slope only costs samples.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "virtual_go/contact/bracketed_root.h"

namespace vg = virtual_go;

namespace {

// The smallest double x in [lo, hi] with f(x) >= 0, by bisection to adjacent doubles (f rising,
// f(lo) < 0 <= f(hi)).
template <class F>
double bisect_to_adjacent(F&& f, double lo, double hi) {
  while (std::nextafter(lo, hi) < hi) {
    const double mid = lo + 0.5 * (hi - lo);
    if (mid <= lo || mid >= hi) break;
    (f(mid) >= 0.0 ? hi : lo) = mid;
  }
  return hi;
}

constexpr double kRelative = 0x1p-50;

}  // namespace

TEST(BracketedRoot, ExactSlopeFindsTheCrossingOfRandomCubicsInFewSamples) {
  // f(x) = a (x - r) + b (x - r)^3, a, b > 0: rising, crossing at r (to the round-off of f).
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int most = 0;
  long total = 0;
  for (int k = 0; k < 2000; ++k) {
    const double scale = std::pow(10.0, -12.0 + 12.0 * u(rng));
    const double r = scale * (0.01 + 0.98 * u(rng)), a = 0.1 + u(rng), b = 10.0 * u(rng) / scale;
    auto value = [&](double x) { return a * (x - r) + b * (x - r) * (x - r) * (x - r); };
    auto f = [&](double x) { return vg::RootSample{value(x), a + 3.0 * b * (x - r) * (x - r)}; };
    int evaluations = 0;
    const double x = vg::rising_root(f, 0.0, f(0.0), scale, value(scale), &evaluations);
    const double reference = bisect_to_adjacent(value, 0.0, scale);
    ASSERT_GE(value(x), 0.0) << k;  // on the event's side
    // Within the tolerance of the first double where the event has happened.
    EXPECT_GE(x, reference) << k;
    EXPECT_LE(x - reference, 2.0 * kRelative * x) << k;
    most = std::max(most, evaluations);
    total += evaluations;
  }
  const double mean = static_cast<double>(total) / 2000.0;
  std::cout << "samples with the exact slope: mean " << mean << ", most " << most << "\n";
  // Bisection to the tolerance would take ~50; Newton with its slope a handful.
  EXPECT_LE(mean, 5.0);
  EXPECT_LE(most, 12);
}

TEST(BracketedRoot, WrongOrMissingSlopeStillConverges) {
  auto value = [](double x) { return std::exp(x) - 2.0; };  // crossing at ln 2
  const double reference = bisect_to_adjacent(value, 0.0, 3.0);
  // Within a factor 2 (or none, or pointing the wrong way) the tolerance holds; a slope c times
  // too steep may stop up to c tolerances beyond the crossing, never before it.
  for (const double slope_factor : {0.0, 1e-3, 0.5, 1.0, 2.0, 1e3, -1.0}) {
    auto f = [&](double x) { return vg::RootSample{value(x), slope_factor * std::exp(x)}; };
    int evaluations = 0;
    const double x = vg::rising_root(f, 0.0, f(0.0), 3.0, value(3.0), &evaluations);
    const double allowance = std::max(2.0, slope_factor);
    EXPECT_GE(value(x), 0.0) << slope_factor;
    EXPECT_GE(x, reference) << slope_factor;
    EXPECT_LE(x - reference, allowance * kRelative * x) << slope_factor;
    EXPECT_LE(evaluations, 200) << slope_factor;
    std::cout << "slope x " << slope_factor << ": " << evaluations << " samples\n";
  }
}

TEST(BracketedRoot, NoCrossingOrBadBracketReturnsTheUpperEnd) {
  int evaluations = 0;
  auto f = [&](double x) { return vg::RootSample{x - 1.0, 1.0}; };
  // f(lo) >= 0: nothing to locate.
  EXPECT_EQ(vg::rising_root(f, 2.0, f(2.0), 3.0, 2.0, &evaluations), 3.0);
  // f(hi) < 0: no crossing in the bracket.
  EXPECT_EQ(vg::rising_root(f, -3.0, f(-3.0), -2.0, -3.0, &evaluations), -2.0);
  EXPECT_EQ(evaluations, 0);
  // An exact zero is returned at once.
  EXPECT_EQ(vg::rising_root(f, 0.0, f(0.0), 4.0, 3.0, &evaluations), 1.0);
  EXPECT_EQ(evaluations, 1);
}
