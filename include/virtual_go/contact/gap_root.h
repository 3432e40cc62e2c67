#pragma once

#include <cmath>
#include <limits>

namespace virtual_go {

// First tau > 0 (s) at which the quadratic lower bound c0 + c1 tau + c2 tau^2 / 2 of a gap
// (c0 in m, c1 in m/s, c2 in m/s^2) reaches 0, for c0 > 0 (0 when c0 <= 0, +inf when it never
// does). The conservative steps of the flight, pair and stone-stone gap bounds all end here.
// Written in the form that does not cancel: 2 c0 / (-c1 + sqrt(c1^2 - 2 c0 c2)) when c1 <= 0,
// (c1 + sqrt(...)) / -c2 when c1 > 0 (then c2 < 0). A cancelling form once made a 6 cm/s bounce
// overshoot by 35 us.
inline double first_gap_root(double c0, double c1, double c2) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(c0 > 0.0)) return 0.0;
  if (c2 == 0.0) return c1 < 0.0 ? c0 / -c1 : kInfinity;
  const double disc = c1 * c1 - 2.0 * c0 * c2;
  if (c2 > 0.0 && (c1 >= 0.0 || disc < 0.0)) return kInfinity;
  if (c1 > 0.0) return (c1 + std::sqrt(disc)) / -c2;
  return 2.0 * c0 / (-c1 + std::sqrt(disc));
}

// The same bound started from 0 (c0 = 0): how long (s) it stays positive; 0 unless c1 > 0.
inline double positive_gap_stretch(double c1, double c2) {
  if (!(c1 > 0.0)) return 0.0;
  return c2 < 0.0 ? -2.0 * c1 / c2 : std::numeric_limits<double>::infinity();
}

}  // namespace virtual_go
