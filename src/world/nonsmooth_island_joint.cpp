// The joint solve of NonsmoothContactOptions::joint_solve (nonsmooth_island_impl.h): projected
// Gauss-Seidel with accumulated impulses, for the island's corrections and for its velocities.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "nonsmooth_island_impl.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/world/island_impulses.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace virtual_go::nonsmooth_island_detail {
namespace {

// Newton steps for a sliding contact's friction (it converges in a few; bisection guards it).
constexpr int kMaxSlidingIterations = 60;

}  // namespace

SolveRow make_row(int a, int b, const Eigen::Vector3d& normal_world,
                  const Eigen::Vector3d& point_world, double mu,
                  const std::vector<RigidBodyState>& states,
                  const std::vector<double>& inverse_mass,
                  const std::vector<Eigen::Matrix3d>& inverse_inertia) {
  SolveRow r;
  r.a = a;
  r.b = b;
  r.normal = normal_world;
  r.rb = point_world - states[b].position_world;
  r.ra = a >= 0 ? Eigen::Vector3d(point_world - states[a].position_world) : Eigen::Vector3d::Zero();
  r.t1 = normal_world.unitOrthogonal();
  r.t2 = normal_world.cross(r.t1);
  r.mu = mu;
  Eigen::Matrix3d k = contact_compliance(1.0 / inverse_mass[b], inverse_inertia[b], r.rb);
  if (a >= 0) k += contact_compliance(1.0 / inverse_mass[a], inverse_inertia[a], r.ra);
  Eigen::Matrix3d basis;
  basis << r.normal, r.t1, r.t2;
  const Eigen::Matrix3d k_axes = basis.transpose() * k * basis;  // in (n, t1, t2)
  r.inverse_k_n = 1.0 / k_axes(0, 0);
  r.k_t = k_axes.block<2, 2>(1, 1);
  r.inverse_k_t = r.k_t.inverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(r.k_t);
  r.k_t_values = eigen.eigenvalues();
  r.k_t_basis = eigen.eigenvectors();
  r.inverse_mass_b = inverse_mass[b];
  r.inverse_mass_a = a >= 0 ? inverse_mass[a] : 0.0;
  Eigen::Matrix3d couple_k = inverse_inertia[b];
  if (a >= 0) couple_k += inverse_inertia[a];
  for (int j = 0; j < 3; ++j) {
    r.arm_b[j] = r.rb.cross(r.axis(j));
    r.turn_b[j] = inverse_inertia[b] * r.arm_b[j];
    r.couple_turn_b[j] = inverse_inertia[b] * r.couple_axis(j);
    r.arm_a[j] = r.ra.cross(r.axis(j));
    r.turn_a[j] =
        a >= 0 ? Eigen::Vector3d(inverse_inertia[a] * r.arm_a[j]) : Eigen::Vector3d::Zero();
    r.couple_turn_a[j] =
        a >= 0 ? Eigen::Vector3d(inverse_inertia[a] * r.couple_axis(j)) : Eigen::Vector3d::Zero();
    const double k_axis = r.couple_axis(j).dot(couple_k * r.couple_axis(j));
    r.inverse_couple_k[j] = k_axis > 0.0 ? 1.0 / k_axis : 0.0;
  }
  return r;
}

namespace {

// Coulomb's sliding friction on row r when the impulse that would stick it, `sticking`, lies
// outside the disk of radius `limit` = mu lambda_n: the impulse on the circle against which the
// slip after it is exactly opposite (maximal dissipation). With the tangential compliance K the
// slip after an impulse l is K (l - sticking), so l = (K + s I)^-1 K sticking for the s >= 0 at
// which |l| = limit. Clamping `sticking` radially instead slips along K l, not along l: for a
// tilted stone (K anisotropic) that turned every sub-step's friction by an angle independent of h,
// and the sliding, spinning stone's velocity error stopped falling at 3e-5 m/s.
Eigen::Vector2d sliding_impulse(const SolveRow& r, const Eigen::Vector2d& sticking, double limit) {
  if (!(limit > 0.0)) return Eigen::Vector2d::Zero();
  // In K's eigenbasis l_i(s) = g_i / (k_i + s): find s by Newton on 1 / |l(s)| - 1 / limit,
  // kept within the bracket [0, |g| / limit] (at its top |l| <= limit), by bisection if need be.
  const Eigen::Vector2d g = r.k_t_basis.transpose() * (r.k_t * sticking);
  double low = 0.0, high = g.norm() / limit, s = 0.0;
  for (int i = 0; i < kMaxSlidingIterations; ++i) {
    const double l1 = g.x() / (r.k_t_values.x() + s), l2 = g.y() / (r.k_t_values.y() + s);
    const double n = std::sqrt(l1 * l1 + l2 * l2);
    const double f = 1.0 / limit - 1.0 / n;
    if (std::abs(f) * limit <= 1e-15) break;
    if (f > 0.0) {
      low = s;
    } else {
      high = s;
    }
    // d(1/n)/ds = (sum g_i^2 / (k_i + s)^3) / n^3
    const double cube = l1 * l1 / (r.k_t_values.x() + s) + l2 * l2 / (r.k_t_values.y() + s);
    double next = s + f * n * n * n / cube;
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - s) <= 1e-15 * (s + r.k_t_values.minCoeff())) break;
    s = next;
  }
  const Eigen::Vector2d l =
      r.k_t_basis * Eigen::Vector2d(g.x() / (r.k_t_values.x() + s), g.y() / (r.k_t_values.y() + s));
  return l * (limit / l.norm());  // on the circle to round-off
}

// One Gauss-Seidel iteration over the rows: each row's normal, then its tangential impulse (the
// pair at once, clamped to the disk mu lambda_n), then its couples (each clamped to l lambda_n:
// a box, not the disk, for rolling).
void iterate(std::vector<SolveRow>& rows, const Motions& m) {
  for (SolveRow& r : rows) {
    const double old_n = r.lambda_n;
    r.lambda_n = std::max(0.0, old_n + (r.target_n - component(r, 0, m)) * r.inverse_k_n);
    apply(r, 0, r.lambda_n - old_n, m);
    const Eigen::Vector2d ut(component(r, 1, m), component(r, 2, m));
    const Eigen::Vector2d old_t(r.lambda_1, r.lambda_2);
    Eigen::Vector2d lt = old_t - r.inverse_k_t * ut;  // sticking
    const double limit = r.mu * r.lambda_n;
    if (lt.norm() > limit) lt = sliding_impulse(r, lt, limit);
    r.lambda_1 = lt.x();
    r.lambda_2 = lt.y();
    apply(r, 1, lt.x() - old_t.x(), m);
    apply(r, 2, lt.y() - old_t.y(), m);
    for (int j = 3; j < kComponents && has_couples(r); ++j) {
      const double limit_j = couple_arm(r, j) * r.lambda_n;
      const double old_c = r.couple[j - 3];
      r.couple[j - 3] =
          std::clamp(old_c - component(r, j, m) * r.inverse_couple_k[j - 3], -limit_j, limit_j);
      apply(r, j, r.couple[j - 3] - old_c, m);
    }
  }
}

}  // namespace

int solve_rows(std::vector<SolveRow>& rows, std::vector<Eigen::Vector3d>& dx,
               std::vector<Eigen::Vector3d>& dtheta, double scale, bool active_set_steps) {
  const Motions m{dx, dtheta};
  for (SolveRow& r : rows) {
    scale = std::max({scale, std::abs(r.target_n), r.u0.norm()});
    r.u0_axes = Eigen::Vector3d(r.normal.dot(r.u0), r.t1.dot(r.u0), r.t2.dot(r.u0));
    r.w0_axes = Eigen::Vector3d(r.t1.dot(r.w0), r.t2.dot(r.w0), r.normal.dot(r.w0));
    // A warm start: the impulses the rows come with act first.
    for (int j = 0; j < kComponents; ++j) apply(r, j, impulse(r, j), m);
  }
  std::vector<double> lever(dx.size(), 0.0);
  for (const SolveRow& r : rows) {
    lever[r.b] = std::max(lever[r.b], r.rb.norm());
    if (r.a >= 0) lever[r.a] = std::max(lever[r.a], r.ra.norm());
  }
  // Accelerated by nonsmooth nonlinear conjugate gradients (Silcowitz, Niebe and Erleben,
  // "A nonsmooth nonlinear conjugate gradient method for interactive contact force problems",
  // The Visual Computer 26, 2010): a sweep's change is taken as a descent direction and the
  // previous direction is added to it with Fletcher and Reeves' beta (the ratio of the squared
  // changes), restarting when the change grows. Its fixed points are Gauss-Seidel's, and the
  // answer is always a sweep's (the cones hold). Plain Gauss-Seidel converges at about 0.998 per
  // sweep in wedges of leaning stones; measured in test_world_crowd with the option, 7.7 M sweeps
  // (1,010 solves capped) before, 2.6 M (47) after, the same rest. Changes are measured in the
  // members' motions (rotations times their contacts' lever), as convergence is.
  std::vector<std::array<double, kComponents>> before(rows.size()), direction(rows.size());
  for (auto& d : direction) d.fill(0.0);
  std::vector<Eigen::Vector3d> previous_dx = dx, previous_dtheta = dtheta;
  std::vector<Eigen::Vector3d> direction_dx(dx.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> direction_dtheta(dx.size(), Eigen::Vector3d::Zero());
  double previous_change = 0.0;  // squared
  // The active-set step's state before it, to go back to where the sweep after it moves the
  // members more than the sweep before it did.
  std::vector<std::array<double, kComponents>> saved(rows.size());
  std::vector<Eigen::Vector3d> saved_dx, saved_dtheta;
  bool stepped = false, stepping = active_set_steps;
  double last_moved = 0.0;
  std::vector<double> history;  // each sweep's largest motion of a member
  int it = 0;
  while (it < kMaxJointIterations) {
    ++it;
    if (stepping && it > kFirstActiveSetStep && (it - kFirstActiveSetStep) % kActiveSetEvery == 0 &&
        active_set_pays(rows, history, kJointTolerance * scale)) {
      for (std::size_t i = 0; i < rows.size(); ++i) {
        for (int j = 0; j < kComponents; ++j) saved[i][j] = impulse(rows[i], j);
      }
      saved_dx = dx;
      saved_dtheta = dtheta;
      stepped = active_set_step(rows, m, scale);
      if (stepped) {
        for (auto& d : direction) d.fill(0.0);
        std::fill(direction_dx.begin(), direction_dx.end(), Eigen::Vector3d::Zero());
        std::fill(direction_dtheta.begin(), direction_dtheta.end(), Eigen::Vector3d::Zero());
        previous_change = 0.0;
        previous_dx = dx;
        previous_dtheta = dtheta;
      } else {
        stepping = false;
      }
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (int j = 0; j < kComponents; ++j) before[i][j] = impulse(rows[i], j);
    }
    iterate(rows, m);
    // Converged when a sweep no longer moves any member (its translation, and its rotation times
    // its contacts' lever): the impulses may still drift where contacts are redundant.
    double moved = 0.0, change = 0.0;
    for (std::size_t i = 0; i < dx.size(); ++i) {
      const double step_x = (dx[i] - previous_dx[i]).squaredNorm();
      const double step_theta =
          (dtheta[i] - previous_dtheta[i]).squaredNorm() * lever[i] * lever[i];
      moved = std::max({moved, step_x, step_theta});
      change += step_x + step_theta;
    }
    if (stepped) {
      stepped = false;
      if (moved > last_moved) {
        // Worse than the sweeps: back to where the step began, and no more steps in this solve.
        for (std::size_t i = 0; i < rows.size(); ++i) {
          for (int j = 0; j < kComponents; ++j) set_impulse(rows[i], j, saved[i][j]);
        }
        dx = saved_dx;
        dtheta = saved_dtheta;
        previous_dx = dx;
        previous_dtheta = dtheta;
        stepping = false;
        if (it == kMaxJointIterations) break;
        continue;
      }
    }
    last_moved = moved;
    history.push_back(std::sqrt(moved));
    if (std::sqrt(moved) <= kJointTolerance * scale || it == kMaxJointIterations) break;
    const double beta = previous_change > 0.0 ? change / previous_change : 0.0;
    previous_change = change;
    // A restart when the change grew (or is not a number: nothing is carried over then).
    const double keep = beta >= 0.0 && beta <= 1.0 ? beta : 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (int j = 0; j < kComponents; ++j) {
        const double push = keep * direction[i][j];
        direction[i][j] = push + (impulse(rows[i], j) - before[i][j]);
        if (push != 0.0) set_impulse(rows[i], j, impulse(rows[i], j) + push);
      }
    }
    for (std::size_t i = 0; i < dx.size(); ++i) {
      const Eigen::Vector3d push_x = keep * direction_dx[i];
      const Eigen::Vector3d push_theta = keep * direction_dtheta[i];
      direction_dx[i] = push_x + (dx[i] - previous_dx[i]);
      direction_dtheta[i] = push_theta + (dtheta[i] - previous_dtheta[i]);
      dx[i] += push_x;
      dtheta[i] += push_theta;
    }
    previous_dx = dx;
    previous_dtheta = dtheta;
  }
  return it;
}

}  // namespace virtual_go::nonsmooth_island_detail

namespace virtual_go {

void NonsmoothIsland::count_joint_solve(int iterations) {
  ++counters_.joint_solves;
  counters_.joint_iterations += iterations;
  if (iterations >= nonsmooth_island_detail::kMaxJointIterations) ++counters_.joint_capped_solves;
}

void NonsmoothIsland::joint_inverses(const std::vector<RigidBodyState>& s,
                                     std::vector<double>& inverse_mass,
                                     std::vector<Eigen::Matrix3d>& inverse_inertia) const {
  inverse_mass.assign(s.size(), 0.0);
  inverse_inertia.assign(s.size(), Eigen::Matrix3d::Zero());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    const MotionModel& model = members_[i].setup.model;
    inverse_mass[i] = 1.0 / model.mass_properties().mass();
    inverse_inertia[i] = model.inertia_world(s[i].orientation).inverse();
  }
}

int NonsmoothIsland::velocities_jointly(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc,
                                        const std::vector<PairContact>& pairs, bool commit) {
  const std::size_t n = s.size();
  using nonsmooth_island_detail::SolveRow;
  std::vector<double> inverse_mass;
  std::vector<Eigen::Matrix3d> inverse_inertia;
  joint_inverses(s, inverse_mass, inverse_inertia);
  std::vector<Eigen::Vector3d> dv(n, Eigen::Vector3d::Zero()), dw(n, Eigen::Vector3d::Zero());
  std::vector<SolveRow> rows;
  std::vector<std::size_t> obstacle_of;
  const auto add = [&](int a, int b, const Eigen::Vector3d& normal, const Eigen::Vector3d& point,
                       double mu) {
    SolveRow r = nonsmooth_island_detail::make_row(a, b, normal, point, mu, s, inverse_mass,
                                                   inverse_inertia);
    r.u0 = point_velocity_world(members_[b].setup.model, s[b], point);
    if (a >= 0) r.u0 -= point_velocity_world(members_[a].setup.model, s[a], point);
    rows.push_back(r);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i]) continue;
    for (int k = 0; k < mc[i].board; ++k) {
      const BoardContact& c = mc[i].contact[k];
      const ContactMaterial& material = c.on_table() ? table_plastic_ : board_plastic_;
      add(-1, static_cast<int>(i), c.lens.normal_world, c.lens.point_world, material.friction);
      rows.back().key = -1 - 2 * static_cast<long>(i) - (c.on_table() ? 1 : 0);
      rows.back().rolling_m = material.rolling_resistance_m;
      rows.back().spinning_m = material.spinning_friction_m;
      rows.back().w0 = members_[i].setup.model.angular_velocity_world(s[i].orientation,
                                                                      s[i].angular_momentum_world);
      obstacle_of.push_back(static_cast<std::size_t>(-1));
    }
  }
  for (const PairContact& p : pairs) {
    if (p.obstacle) {
      add(-1, static_cast<int>(p.a), -p.normal_world, p.point_world, stone_plastic_.friction);
      rows.back().key = -1000000 - static_cast<long>(p.a * obstacles_.size() + p.b);
      obstacle_of.push_back(p.b);
    } else {
      add(static_cast<int>(p.a), static_cast<int>(p.b), p.normal_world, p.point_world,
          stone_plastic_.friction);
      rows.back().key = 1 + static_cast<long>(p.a * n + p.b);
      obstacle_of.push_back(static_cast<std::size_t>(-1));
    }
  }
  nonsmooth_island_detail::load_warm(rows, warm_velocities_);
  const int sweeps = nonsmooth_island_detail::solve_rows(rows, dv, dw);
  if (commit) {
    nonsmooth_island_detail::store_warm(rows, warm_velocities_);
    count_joint_solve(sweeps);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i] || (dv[i].isZero(0.0) && dw[i].isZero(0.0))) continue;
    const MotionModel& model = members_[i].setup.model;
    s[i].velocity_world += dv[i];
    s[i].angular_momentum_world += model.inertia_world(s[i].orientation) * dw[i];
    mc[i].loaded = true;
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].lambda_n > 0.0 && obstacle_of[r] != static_cast<std::size_t>(-1)) {
      obstacle_acted_[obstacle_of[r]] = 1;
    }
  }
  // The contacts that acted, counted as the sweeps count their impulses.
  for (std::size_t r = 0; commit && r < rows.size(); ++r) {
    const SolveRow& row = rows[r];
    if (row.lambda_n == 0.0 && row.lambda_1 == 0.0 && row.lambda_2 == 0.0) continue;
    ++counters_.impulses;
    if (row.a >= 0) ++counters_.pair_impulses;
    if (obstacle_of[r] != static_cast<std::size_t>(-1)) ++counters_.obstacle_impulses;
  }
  return sweeps;
}

}  // namespace virtual_go
