// Independent references for the contact tests, written from the definitions and never calling
// the code under test: the lens as the intersection of two balls (its support mapping and reach
// from CONTACT geometry in docs/physics.md), support mappings of a point, a segment and a box,
// and GJK distance (Gilbert, Johnson & Keerthi 1988) between two convex sets given by support
// mappings, with a brute-force closest-point-of-simplex step (all faces of the simplex tried).
// GJK returns a bracket [lower, upper] of the distance: upper = |v| is the length of a point of
// A - B, lower the separation along v; the tests check the code against that bracket.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vgtest {

// The lens of width 2a and height 2c at centre x with unit axis b, world frame.
struct LensReference {
  double a, c;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::UnitZ();

  double sphere_radius() const { return (a * a + c * c) / (2.0 * c); }
  double sphere_offset() const { return sphere_radius() - c; }
  // Largest u . p over the lens for a direction u (any length > 0): the top cap lies on the
  // sphere centred at x - d b, the bottom cap on the one at x + d b; a direction within the
  // angle beta (cos beta = d / R) of +b or -b meets a cap, any other the rim.
  Eigen::Vector3d support(const Eigen::Vector3d& direction) const {
    const Eigen::Vector3d u = direction.normalized();
    const double r = sphere_radius(), d = sphere_offset(), ct = u.dot(b);
    if (ct >= d / r) return x - d * b + r * u;
    if (ct <= -d / r) return x + d * b + r * u;
    const Eigen::Vector3d radial = u - ct * b;
    return x + a * radial.normalized();
  }
  // How far the lens extends below its centre along -n: max over the lens of -n . (p - x).
  double reach(const Eigen::Vector3d& n) const { return -n.dot(support(-n) - x); }
  // True when p is inside both balls.
  bool contains(const Eigen::Vector3d& p) const {
    const double r = sphere_radius(), d = sphere_offset();
    return (p - (x + d * b)).norm() <= r && (p - (x - d * b)).norm() <= r;
  }
};

struct BoxReference {  // axis-aligned: [-hx, hx] x [-hy, hy] x [z_lo, z_hi]
  double hx, hy, z_lo, z_hi;
  Eigen::Vector3d support(const Eigen::Vector3d& u) const {
    return Eigen::Vector3d(u.x() >= 0 ? hx : -hx, u.y() >= 0 ? hy : -hy, u.z() >= 0 ? z_hi : z_lo);
  }
};

struct SegmentReference {
  Eigen::Vector3d p, q;
  Eigen::Vector3d support(const Eigen::Vector3d& u) const { return u.dot(q - p) >= 0 ? q : p; }
};

struct PointReference {
  Eigen::Vector3d p;
  Eigen::Vector3d support(const Eigen::Vector3d&) const { return p; }
};

struct GjkResult {
  double upper = 0.0;  // |v|: a point of A - B this close to the origin exists
  double lower = -std::numeric_limits<double>::infinity();  // every point of A - B is this far
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero(), point_b = Eigen::Vector3d::Zero();
  bool overlap = false;
  int iterations = 0;
};

// With stop_once_apart the search ends as soon as a positive lower bound proves the sets apart.
template <class ShapeA, class ShapeB>
GjkResult gjk_distance(const ShapeA& shape_a, const ShapeB& shape_b, int max_iterations = 300,
                       bool stop_once_apart = false) {
  struct Vertex {
    Eigen::Vector3d w, a, b;
  };
  auto vertex = [&](const Eigen::Vector3d& dir) {  // support of A - B along dir
    const Eigen::Vector3d a = shape_a.support(dir), b = shape_b.support(-dir);
    return Vertex{a - b, a, b};
  };
  std::vector<Vertex> simplex{vertex(Eigen::Vector3d(1.0, 0.3, 0.2))};
  std::vector<double> lambda{1.0};
  Eigen::Vector3d v = simplex[0].w;
  GjkResult result;
  for (int it = 0; it < max_iterations; ++it) {
    result.iterations = it + 1;
    const double vn = v.norm();
    if (vn < 1e-300) {
      result.overlap = true;
      break;
    }
    const Eigen::Vector3d axis = v / vn;
    const Vertex w = vertex(-axis);
    result.lower = std::max(result.lower, axis.dot(w.w));
    if (vn - result.lower <= 1e-17 * std::max(1.0, vn)) break;
    if (stop_once_apart && result.lower > 0.0) break;
    bool duplicate = false;
    for (const Vertex& s : simplex) duplicate = duplicate || (s.w - w.w).norm() == 0.0;
    if (duplicate) break;
    simplex.push_back(w);
    // Closest point of the simplex's hull to the origin: over every subset, the projection of
    // the origin onto its affine hull, kept if all barycentric weights are positive.
    const int k = static_cast<int>(simplex.size());
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> best_subset;
    std::vector<double> best_lambda;
    for (int mask = 1; mask < (1 << k); ++mask) {
      std::vector<int> idx;
      for (int i = 0; i < k; ++i) {
        if (mask & (1 << i)) idx.push_back(i);
      }
      const int m = static_cast<int>(idx.size());
      std::vector<double> lam(m, 1.0);
      Eigen::Vector3d point = simplex[idx[0]].w;
      if (m > 1) {
        Eigen::MatrixXd dm(3, m - 1);
        for (int j = 1; j < m; ++j) dm.col(j - 1) = simplex[idx[j]].w - simplex[idx[0]].w;
        const Eigen::MatrixXd g = dm.transpose() * dm;
        const Eigen::VectorXd rhs = -dm.transpose() * simplex[idx[0]].w;
        Eigen::FullPivLU<Eigen::MatrixXd> lu(g);
        if (lu.rank() < m - 1) continue;
        const Eigen::VectorXd mu = lu.solve(rhs);
        lam[0] = 1.0 - mu.sum();
        bool positive = lam[0] > 0.0;
        for (int j = 1; j < m; ++j) {
          lam[j] = mu(j - 1);
          positive = positive && lam[j] > 0.0;
        }
        if (!positive) continue;
        point = simplex[idx[0]].w + dm * mu;
      }
      if (point.norm() < best) {
        best = point.norm();
        best_subset = idx;
        best_lambda = lam;
        v = point;
      }
    }
    std::vector<Vertex> reduced;
    for (int i : best_subset) reduced.push_back(simplex[i]);
    simplex = reduced;
    lambda = best_lambda;
    if (simplex.size() == 4) {
      result.overlap = true;
      break;
    }
  }
  result.upper = result.overlap ? 0.0 : v.norm();
  for (size_t i = 0; i < simplex.size(); ++i) {
    result.point_a += lambda[i] * simplex[i].a;
    result.point_b += lambda[i] * simplex[i].b;
  }
  return result;
}

}  // namespace vgtest
