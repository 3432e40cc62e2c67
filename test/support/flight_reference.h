// The flight of a lens in closed form, written in the test from DESIGN.md's formulas (exact
// parabola for the centre, the torque-free axisymmetric top or a constant world omega for the
// orientation), never calling the code under test; and the separating-axis gap of a lens to a
// line by a brute-force scan over directions perpendicular to it, refined by Brent's method.
#pragma once

#include <Eigen/Core>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <vector>

#include "physics_reference.h"
#include "convex_reference.h"

namespace vgtest {

struct FlightReference {
  double a, c;  // lens half width and half height, m
  Eigen::Vector3d x0, v0, g;
  AxisymmetricTop top;  // used unless constant_omega
  bool constant_omega = false;
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();  // for constant_omega

  Quat orientation_at(double t) const {
    return constant_omega ? qmul(axis_angle(t * omega_world), top.q0) : top.orientation_at(t);
  }
  Eigen::Vector3d position_at(double t) const { return x0 + v0 * t + 0.5 * g * t * t; }
  LensReference lens_at(double t) const {
    LensReference ref{a, c};
    ref.x = position_at(t);
    ref.b = rotate(orientation_at(t), Eigen::Vector3d::UnitZ());
    return ref;
  }
};

// max over unit n perpendicular to e of n . (x - p0) - reach(n): the lens's signed distance to
// the line through p0 along e.
inline double line_gap_by_scan(const LensReference& ref, const Eigen::Vector3d& p0,
                               const Eigen::Vector3d& e, Eigen::Vector3d* best_n = nullptr) {
  Eigen::Vector3d u1 =
      (std::abs(e.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
  u1 = (u1 - u1.dot(e) * e).normalized();
  const Eigen::Vector3d u2 = e.cross(u1);
  auto n_of = [&](double psi) { return Eigen::Vector3d(std::cos(psi) * u1 + std::sin(psi) * u2); };
  auto f = [&](double psi) {
    const Eigen::Vector3d n = n_of(psi);
    return n.dot(ref.x - p0) - ref.reach(n);
  };
  constexpr int kScan = 3600;
  const double h = 2 * M_PI / kScan;
  std::vector<double> values(kScan);
  for (int j = 0; j < kScan; ++j) values[j] = f(j * h);
  double best = -1e9, best_psi = 0;
  for (int j = 0; j < kScan; ++j) {
    if (values[j] < values[(j + 1) % kScan] || values[j] < values[(j + kScan - 1) % kScan]) {
      continue;
    }
    const auto r = boost::math::tools::brent_find_minima([&](double t) { return -f(t); },
                                                         (j - 1) * h, (j + 1) * h, 40);
    if (-r.second > best) {
      best = -r.second;
      best_psi = r.first;
    }
  }
  if (best_n) *best_n = n_of(best_psi);
  return best;
}

}  // namespace vgtest
