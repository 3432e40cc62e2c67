// The crossing of a rising event function on a bracket, by Newton's method with the function's
// own slope, safeguarded by the bracket (secant, then bisection, when a Newton step leaves it).
// The impulse process (src/contact/impulse_process.h) locates the end of compression and of
// restitution this way: each evaluation there is a full Runge-Kutta re-step, and its slope is
// known in closed form (du_n/dp = K_n . (dP_t/dp, 1), dW/dp = u_n), so two or three evaluations
// do what a derivative-free bracketing solver (TOMS 748) needs about five for. The answer has the
// meaning and tolerance of toms748_solve with eps_tolerance(digits - 2): a point hi with
// f(hi) >= 0 within 2^-50 hi of the crossing, shown either by a bracket [lo, hi], f(lo) < 0,
// hi - lo <= 2^-50 hi (or adjacent doubles), or by Newton's correction f(hi) / f'(hi) <= 2^-51 hi.
#pragma once

#include <cmath>
#include <limits>

namespace virtual_go {

struct RootSample {
  double value = 0.0;  // f(x)
  // f'(x). Within a factor 2 the answer keeps the tolerance; an estimate off by a factor c
  // more may end the search up to c times the tolerance from the crossing (never on the wrong
  // side, never slower than bisection).
  double slope = 0.0;
};

// f(x) returns RootSample at x in (lo, hi). Requires lo < hi, f(lo) = at_lo.value < 0 <=
// f(hi) = f_hi (else returns hi). Returns the upper end of the final bracket: a point where the
// event has happened (f >= 0) within the tolerance of the crossing. `evaluations`, if given, is
// increased by the number of calls of f.
template <class F>
double rising_root(F&& f, double lo, RootSample at_lo, double hi, double f_hi,
                   int* evaluations = nullptr, int max_evaluations = 200) {
  if (!(at_lo.value < 0.0) || !(f_hi >= 0.0) || !(lo < hi)) return hi;
  constexpr double kRelative = 0x1p-50;  // eps_tolerance(digits - 2) of Boost.Math
  double f_lo = at_lo.value;
  auto converged = [&] {
    return hi - lo <= kRelative * std::abs(hi) || std::nextafter(lo, hi) == hi;
  };
  // Newton from lo first: with the slope exact, the next point is within round-off of the crossing.
  double x = at_lo.slope > 0.0 ? lo - f_lo / at_lo.slope : 0.5 * (lo + hi);
  // The lengths of the last two steps between samples (none yet).
  double step_one_ago = std::numeric_limits<double>::infinity(), step_two_ago = step_one_ago;
  for (int k = 0; k < max_evaluations && !converged(); ++k) {
    if (!(x > lo && x < hi)) {  // outside the bracket: the secant, else the middle
      x = lo - f_lo * ((hi - lo) / (f_hi - f_lo));
      if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    }
    const RootSample s = f(x);
    if (evaluations) ++*evaluations;
    if (s.value >= 0.0) {
      hi = x;
      f_hi = s.value;
      // On the event's side with Newton's own correction below half the tolerance: the crossing
      // is that close (the correction's error is second order in it), no other sample needed.
      if (s.value == 0.0 || (s.slope > 0.0 && s.value <= 0.5 * kRelative * std::abs(x) * s.slope)) {
        return hi;
      }
    } else {
      lo = x;
      f_lo = s.value;
    }
    if (converged()) break;
    double next = s.slope > 0.0 ? x - s.value / s.slope : 0.5 * (lo + hi);
    const double tolerance = kRelative * std::abs(hi);
    if (std::abs(next - x) < 0.5 * tolerance) {
      // A Newton step below the tolerance would land on the same side again: step just across
      // the crossing instead (by half the tolerance), so that the next sample closes the bracket.
      next = s.value < 0.0 ? x + 0.5 * tolerance : x - 0.5 * tolerance;
    } else if (!(next > lo && next < hi) || std::abs(next - x) > 0.5 * step_two_ago) {
      // Newton leaves the bracket, or its steps do not shrink (a poor slope; Numerical
      // Recipes' rtsafe): the middle, so that no slope makes this much slower than bisection.
      next = 0.5 * (lo + hi);
    }
    step_two_ago = step_one_ago;
    step_one_ago = std::abs(next - x);
    x = next;
  }
  return hi;
}

}  // namespace virtual_go
