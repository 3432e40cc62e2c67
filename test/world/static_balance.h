// Static balance of stones at rest, written from the definitions for the many-stone world tests:
// whether contact forces and couples exist, each inside its contact law, that hold every stone's
// weight and its moment. A state the World calls resting must admit them: a stone whose contacts
// cannot hold it would move. The contacts are found with the test's own lens model
// (convex_reference.h): the board where a stone's lowest point is within `touch_m` of the top face
// z = 0, a pair where the supporting-plane gap (many_stones_support.h) is within `touch_m`. The
// laws are the materials' (contact/material.h): normal force N >= 0, friction |f_t| <= mu N,
// rolling couple |M_t| <= l_r N, spinning couple |M_n| <= l_s N. The cone and the couples' disk are
// replaced by polytopes around them (a 16-sided pyramid of slope mu / cos(pi / 16), the square
// of half side l_r), so the check is never stricter than the laws: it only fails a state that the
// laws cannot hold. The forces are found by non-negative least squares over the polytopes' edges
// (Lawson and Hanson, "Solving Least Squares Problems", 1974, ch. 23; written here because
// Debian 12's Eigen 3.4 has no NNLS module), and the residual is the part of the weights'
// wrenches that no admissible forces carry.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "world/many_stones_support.h"

namespace worldtest {

// min ||A x - b|| over x >= 0 (Lawson-Hanson active set). Returns x.
inline Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& A,
                                                  const Eigen::VectorXd& b,
                                                  int max_iterations = 2000) {
  const Eigen::Index n = A.cols();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double tol = 1e-12 * std::max(1.0, A.cwiseAbs().maxCoeff()) * std::max(1.0, b.norm());
  const auto solve_passive = [&]() {
    std::vector<Eigen::Index> idx;
    for (Eigen::Index j = 0; j < n; ++j)
      if (passive[static_cast<std::size_t>(j)]) idx.push_back(j);
    Eigen::MatrixXd Ap(A.rows(), static_cast<Eigen::Index>(idx.size()));
    for (std::size_t k = 0; k < idx.size(); ++k)
      Ap.col(static_cast<Eigen::Index>(k)) = A.col(idx[k]);
    const Eigen::VectorXd zp = Ap.completeOrthogonalDecomposition().solve(b);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    for (std::size_t k = 0; k < idx.size(); ++k) z[idx[k]] = zp[static_cast<Eigen::Index>(k)];
    return z;
  };
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::VectorXd w = A.transpose() * (b - A * x);
    Eigen::Index best = -1;
    double best_w = tol;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!passive[static_cast<std::size_t>(j)] && w[j] > best_w) best_w = w[j], best = j;
    }
    if (best < 0) break;  // Kuhn-Tucker conditions hold
    passive[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < max_iterations; ++inner) {
      const Eigen::VectorXd z = solve_passive();
      bool feasible = true;
      double alpha = 1.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[static_cast<std::size_t>(j)] && z[j] <= 0.0) {
          feasible = false;
          alpha = std::min(alpha, x[j] / (x[j] - z[j]));
        }
      }
      if (feasible) {
        x = z;
        break;
      }
      x += alpha * (z - x);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[static_cast<std::size_t>(j)] && x[j] <= tol) {
          passive[static_cast<std::size_t>(j)] = false;
          x[j] = 0.0;
        }
      }
    }
  }
  return x;
}

// A wrench left unheld (in units of m g, m g a) as large as this would move a stone faster than
// the rest speed (1e-5 m/s) within the rest time (0.01 s): 1e-5 / (0.01 g) ~ 1e-4.
constexpr double kHeldResidual = 1e-4;

struct BalanceContact {
  std::size_t a = 0, b = 0;  // b receives +wrench, a -wrench; a = b: the board (on b only)
  bool board = false;
  Eigen::Vector3d point_world, normal_world;  // normal from a into b (board: +z)
  double gap_m = 0.0;
};

struct BalanceResult {
  std::vector<BalanceContact> contacts;
  // Per stone, the wrench that no admissible contact forces carry: force / (m |g|) and
  // torque about G / (m |g| a), dimensionless.
  std::vector<double> force_residual, torque_residual;
};

struct BalanceLaws {
  double mu_board, l_r_board, l_s_board, mu_stone, l_r_stone, l_s_stone;
};
inline BalanceLaws laws_of(const vg::WorldConfig& c) {
  return {c.board_material.friction,
          c.board_material.rolling_resistance_m,
          c.board_material.spinning_friction_m,
          c.stone_material.friction,
          c.stone_material.rolling_resistance_m,
          c.stone_material.spinning_friction_m};
}

// The contact between two lenses: the normal where the supporting-plane gap is largest
// (pair_gap_bound_with_normal), the point halfway between the two supporting points.
inline BalanceContact pair_contact_reference(const vgtest::LensReference& a,
                                             const vgtest::LensReference& b) {
  const SupportGap bound = pair_gap_bound_with_normal(a, b);
  BalanceContact c;
  c.normal_world = bound.normal_world;
  c.gap_m = bound.gap_m;
  c.point_world = 0.5 * (a.support(c.normal_world) + b.support(-c.normal_world));
  return c;
}

// The stones of `world` at their present states, with gravity g_world. With `checked` (one flag
// per stone), only those stones are balanced; the others are fixed supports (their contacts act
// on the checked stones only) and get residual 0.
inline BalanceResult static_balance(const vg::World& world, const Eigen::Vector3d& g_world,
                                    const BalanceLaws& laws, double touch_m,
                                    std::vector<bool> checked = {}) {
  const std::size_t n = world.stone_count();
  if (checked.empty()) checked.assign(n, true);
  BalanceResult r;
  std::vector<StoneFacts> facts(n);
  std::vector<vgtest::LensReference> lens;
  for (std::size_t i = 0; i < n; ++i) {
    facts[i] = facts_of(world, i);
    lens.push_back(lens_of(facts[i], world.state(i)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    BalanceContact c;
    c.a = c.b = i;
    c.board = true;
    c.point_world = lens[i].support(-Eigen::Vector3d::UnitZ());
    c.normal_world = Eigen::Vector3d::UnitZ();
    c.gap_m = c.point_world.z();
    if (checked[i] && c.gap_m <= touch_m) r.contacts.push_back(c);
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!checked[i] && !checked[j]) continue;
      if ((lens[j].x - lens[i].x).norm() > facts[i].a_m + facts[j].a_m + touch_m) continue;
      BalanceContact p = pair_contact_reference(lens[i], lens[j]);
      p.a = i;
      p.b = j;
      if (p.gap_m <= touch_m) r.contacts.push_back(p);
    }
  }
  // Stones joined by contacts are balanced together, each group on its own (one least-squares
  // problem per group keeps the problems small).
  std::vector<std::size_t> group(n);
  for (std::size_t i = 0; i < n; ++i) group[i] = i;
  const auto root = [&](std::size_t i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  for (const BalanceContact& c : r.contacts) {
    if (!c.board && checked[c.a] && checked[c.b]) group[root(c.a)] = root(c.b);
  }
  r.force_residual.assign(n, 0.0);
  r.torque_residual.assign(n, 0.0);
  const int sides = 16;
  const double g = g_world.norm();
  for (std::size_t leader = 0; leader < n; ++leader) {
    if (!checked[leader] || root(leader) != leader) continue;
    std::vector<Eigen::Index> row(n, -1);  // a member's first row
    Eigen::Index rows = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (checked[i] && root(i) == leader) row[i] = rows, rows += 6;
    }
    // Columns: each contact's generators (the normal plus a pyramid edge of the friction cone,
    // with a corner of the couples' box), as wrenches on the members; rows: 6 per member,
    // scaled by m g and m g a.
    std::vector<Eigen::VectorXd> columns;
    for (const BalanceContact& c : r.contacts) {
      if (row[c.b] < 0 && (c.board || row[c.a] < 0)) continue;
      const double mu = (c.board ? laws.mu_board : laws.mu_stone) / std::cos(M_PI / sides);
      const double l_r = c.board ? laws.l_r_board : laws.l_r_stone;
      const double l_s = c.board ? laws.l_s_board : laws.l_s_stone;
      const Eigen::Vector3d t1 = c.normal_world.unitOrthogonal(), t2 = c.normal_world.cross(t1);
      for (int k = 0; k < sides; ++k) {
        const double phi = 2.0 * M_PI * k / sides;
        const Eigen::Vector3d f = c.normal_world + mu * (std::cos(phi) * t1 + std::sin(phi) * t2);
        for (int corner = 0; corner < 8; ++corner) {
          const Eigen::Vector3d m = (corner & 1 ? l_r : -l_r) * t1 +
                                    (corner & 2 ? l_r : -l_r) * t2 +
                                    (corner & 4 ? l_s : -l_s) * c.normal_world;
          Eigen::VectorXd col = Eigen::VectorXd::Zero(rows);
          const auto add = [&](std::size_t i, double sign) {
            if (row[i] < 0) return;
            const double w = facts[i].mass_kg * g, arm = facts[i].a_m;
            col.segment<3>(row[i]) += sign * f / w;
            col.segment<3>(row[i] + 3) +=
                sign * ((c.point_world - lens[i].x).cross(f) + m) / (w * arm);
          };
          add(c.b, 1.0);
          if (!c.board) add(c.a, -1.0);
          columns.push_back(col);
        }
      }
    }
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(rows);
    for (std::size_t i = 0; i < n; ++i) {
      if (row[i] >= 0) rhs.segment<3>(row[i]) = -g_world / g;  // minus the weight / (m g)
    }
    Eigen::MatrixXd A(rows, static_cast<Eigen::Index>(columns.size()));
    for (std::size_t k = 0; k < columns.size(); ++k)
      A.col(static_cast<Eigen::Index>(k)) = columns[k];
    const Eigen::VectorXd residual =
        columns.empty() ? Eigen::VectorXd(-rhs)
                        : Eigen::VectorXd(A * non_negative_least_squares(A, rhs) - rhs);
    for (std::size_t i = 0; i < n; ++i) {
      if (row[i] < 0) continue;
      r.force_residual[i] = residual.segment<3>(row[i]).norm();
      r.torque_residual[i] = residual.segment<3>(row[i] + 3).norm();
    }
  }
  return r;
}

// Prints "[ measured ] <what>: n of m stones at rest not held by their contacts within touch_m,
// largest unheld wrench w" and returns n; with `checked`, only those stones (the others fixed
// supports, as static_balance takes them).
inline int print_unheld(const char* what, const vg::World& world, const Eigen::Vector3d& g_world,
                        double touch_m = 1e-9, const std::vector<bool>& checked = {}) {
  const BalanceResult b = static_balance(world, g_world, laws_of(world.config()), touch_m, checked);
  int unheld = 0, counted = 0;
  double largest = 0.0;
  for (std::size_t i = 0; i < world.stone_count(); ++i) {
    if (!checked.empty() && !checked[i]) continue;
    ++counted;
    const double residual = std::max(b.force_residual[i], b.torque_residual[i]);
    largest = std::max(largest, residual);
    unheld += residual > kHeldResidual;
  }
  std::printf(
      "[ measured ] %s: %d of %d stones at rest not held by their contacts within %g m (%zu "
      "contacts), largest unheld wrench %.3g of m g (or m g a)\n",
      what, unheld, counted, touch_m, b.contacts.size(), largest);
  return unheld;
}

}  // namespace worldtest
