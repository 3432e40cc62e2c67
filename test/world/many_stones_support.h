// Shared pieces of the many-stone world tests, written from the definitions: each stone's mass,
// principal moments and lens read from its body (the inputs), and from them the test's own
// energy, linear momentum and angular momentum about the world origin, the lens as the
// intersection of two balls (convex_reference.h) and a proven lower bound of the signed distance
// of two lenses (the gap between two supporting planes, maximised over directions).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "support/convex_reference.h"
#include "virtual_go/world/world.h"

namespace worldtest {

namespace vg = virtual_go;

// A stone's inputs: mass, principal moments (I1, I1, I3) and lens half width and half height.
struct StoneFacts {
  double mass_kg = 0.0;
  Eigen::Vector3d moments_body = Eigen::Vector3d::Zero();
  double a_m = 0.0, c_m = 0.0;
};

inline StoneFacts facts_of_body(const vg::World& world, std::size_t body) {
  const vg::WorldBodyModel& b = world.body_model(body);
  const vg::MassProperties& mp = b.setup().model.mass_properties();
  return {mp.mass(), mp.principal_moments_body(), b.body().shape.half_width(),
          b.body().shape.half_height()};
}
inline StoneFacts facts_of(const vg::World& world, std::size_t stone) {
  return facts_of_body(world, world.body_of(stone));
}

inline Eigen::Matrix3d inertia_world(const StoneFacts& f, const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  return r * f.moments_body.asDiagonal() * r.transpose();
}
inline Eigen::Vector3d omega_of(const StoneFacts& f, const vg::RigidBodyState& s) {
  return inertia_world(f, s.orientation).ldlt().solve(s.angular_momentum_world);
}
// 1/2 m v^2 + 1/2 omega . L - m g . x, J.
inline double energy_of(const StoneFacts& f, const vg::RigidBodyState& s,
                        const Eigen::Vector3d& gravity_world) {
  return 0.5 * f.mass_kg * s.velocity_world.squaredNorm() +
         0.5 * omega_of(f, s).dot(s.angular_momentum_world) -
         f.mass_kg * gravity_world.dot(s.position_world);
}
// Angular momentum about the world origin: spin plus the orbital part x × m v.
inline Eigen::Vector3d angular_momentum_about_origin(const StoneFacts& f,
                                                     const vg::RigidBodyState& s) {
  return s.angular_momentum_world + s.position_world.cross(f.mass_kg * s.velocity_world);
}

inline vgtest::LensReference lens_of(const StoneFacts& f, const vg::RigidBodyState& s) {
  vgtest::LensReference l{f.a_m, f.c_m};
  l.x = s.position_world;
  l.b = s.orientation.normalized() * Eigen::Vector3d::UnitZ();
  return l;
}

// A lower bound of the signed distance between two lenses: the gap between the two supporting
// planes with normal n, F(n) = n . (s_B(-n) - s_A(n)), is below the signed distance for every
// unit n and equals it at the best n (for overlapping lenses, minus the penetration depth). Its
// largest value is sought from a scan of directions (a Fibonacci sphere and the centre line),
// refined by a pattern search on the sphere with shrinking steps.
// With the direction n (from a towards b) where it is largest: for touching lenses, their
// contact normal.
struct SupportGap {
  double gap_m;
  Eigen::Vector3d normal_world;
};
inline SupportGap pair_gap_bound_with_normal(const vgtest::LensReference& a,
                                             const vgtest::LensReference& b) {
  const auto along = [&](const Eigen::Vector3d& n) { return n.dot(b.support(-n) - a.support(n)); };
  Eigen::Vector3d best_n = (b.x - a.x).normalized();
  double best = along(best_n);
  const int scan = 2000;
  for (int k = 0; k < scan; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / scan, r = std::sqrt(1.0 - z * z);
    const double phi = k * M_PI * (3.0 - std::sqrt(5.0));
    const Eigen::Vector3d n(r * std::cos(phi), r * std::sin(phi), z);
    const double f = along(n);
    if (f > best) best = f, best_n = n;
  }
  for (double step = 0.05; step > 1e-12; step *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      const Eigen::Vector3d u = best_n.unitOrthogonal(), v = best_n.cross(u);
      for (const Eigen::Vector3d& d : {u, Eigen::Vector3d(-u), v, Eigen::Vector3d(-v)}) {
        const Eigen::Vector3d n = (best_n + step * d).normalized();
        const double f = along(n);
        if (f > best) best = f, best_n = n, improved = true;
      }
    }
  }
  return {best, best_n};
}
inline double pair_gap_bound(const vgtest::LensReference& a, const vgtest::LensReference& b) {
  return pair_gap_bound_with_normal(a, b).gap_m;
}

// The smallest pair_gap_bound over every pair of stones whose balls of radius a (each lens lies
// inside the ball of its half width about its centre) meet; +infinity when none do.
inline double smallest_pair_gap(const vg::World& world) {
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < world.stone_count(); ++i) {
    const StoneFacts fi = facts_of(world, i);
    for (std::size_t j = i + 1; j < world.stone_count(); ++j) {
      const StoneFacts fj = facts_of(world, j);
      const vg::RigidBodyState &si = world.state(i), &sj = world.state(j);
      if ((sj.position_world - si.position_world).norm() > fi.a_m + fj.a_m + 1e-6) continue;
      smallest = std::min(smallest, pair_gap_bound(lens_of(fi, si), lens_of(fj, sj)));
    }
  }
  return smallest;
}

}  // namespace worldtest
