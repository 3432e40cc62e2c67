// The joint solve of NonsmoothContactOptions::joint_solve (nonsmooth_island_impl.h): projected
// Gauss-Seidel with accumulated impulses, for the island's corrections and for its velocities.
#include <algorithm>
#include <cmath>
#include <vector>

#include "nonsmooth_island_impl.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/world/island_impulses.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace virtual_go::nonsmooth_island_detail {
namespace {

// Gauss-Seidel iterations per solve, and the largest motion of a member over an iteration
// (relative to the largest target or contact velocity) below which it stops.
constexpr int kMaxJointIterations = 1000;
constexpr double kJointTolerance = 1e-9;

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
  r.k = basis.transpose() * k * basis;
  return r;
}

int solve_rows(std::vector<SolveRow>& rows, const std::vector<double>& inverse_mass,
               const std::vector<Eigen::Matrix3d>& inverse_inertia,
               std::vector<Eigen::Vector3d>& dx, std::vector<Eigen::Vector3d>& dtheta) {
  const auto displacement = [&](const SolveRow& r) {
    Eigen::Vector3d u = r.u0 + dx[r.b] + dtheta[r.b].cross(r.rb);
    if (r.a >= 0) u -= dx[r.a] + dtheta[r.a].cross(r.ra);
    return u;
  };
  const auto apply = [&](const SolveRow& r, const Eigen::Vector3d& p) {
    dx[r.b] += inverse_mass[r.b] * p;
    dtheta[r.b] += inverse_inertia[r.b] * r.rb.cross(p);
    if (r.a >= 0) {
      dx[r.a] -= inverse_mass[r.a] * p;
      dtheta[r.a] -= inverse_inertia[r.a] * r.ra.cross(p);
    }
  };
  double scale = 0.0;
  for (const SolveRow& r : rows) scale = std::max({scale, std::abs(r.target_n), r.u0.norm()});
  // A warm start: the impulses the rows come with act first.
  for (const SolveRow& r : rows) {
    apply(r, r.lambda_n * r.normal + r.lambda_1 * r.t1 + r.lambda_2 * r.t2);
    const Eigen::Vector3d angular =
        r.couple.x() * r.t1 + r.couple.y() * r.t2 + r.couple.z() * r.normal;
    dtheta[r.b] += inverse_inertia[r.b] * angular;
    if (r.a >= 0) dtheta[r.a] -= inverse_inertia[r.a] * angular;
  }
  std::vector<Eigen::Vector3d> previous_dx = dx, previous_dtheta = dtheta;
  std::vector<double> lever(dx.size(), 0.0);
  for (const SolveRow& r : rows) {
    lever[r.b] = std::max(lever[r.b], r.rb.norm());
    if (r.a >= 0) lever[r.a] = std::max(lever[r.a], r.ra.norm());
  }
  int it = 0;
  while (it < kMaxJointIterations) {
    ++it;
    for (SolveRow& r : rows) {
      const Eigen::Vector3d u = displacement(r);
      const double old_n = r.lambda_n;
      r.lambda_n = std::max(0.0, old_n + (r.target_n - r.normal.dot(u)) / r.k(0, 0));
      apply(r, (r.lambda_n - old_n) * r.normal);
      const Eigen::Vector3d v = displacement(r);
      const Eigen::Vector2d ut(r.t1.dot(v), r.t2.dot(v));
      const Eigen::Vector2d old_t(r.lambda_1, r.lambda_2);
      Eigen::Vector2d lt = old_t - r.k.block<2, 2>(1, 1).inverse() * ut;
      const double limit = r.mu * r.lambda_n;
      if (lt.norm() > limit) lt *= limit / lt.norm();
      r.lambda_1 = lt.x();
      r.lambda_2 = lt.y();
      const Eigen::Vector2d d = lt - old_t;
      apply(r, d.x() * r.t1 + d.y() * r.t2);
      if (r.rolling_m > 0.0 || r.spinning_m > 0.0) {
        // Relative rotation (b against a) and its compliance about the axes.
        const auto rotation = [&]() {
          Eigen::Vector3d w = dtheta[r.b];
          if (r.a >= 0) w -= dtheta[r.a];
          return Eigen::Vector3d(r.w0 + w);
        };
        Eigen::Matrix3d c = inverse_inertia[r.b];
        if (r.a >= 0) c += inverse_inertia[r.a];
        const auto turn = [&](const Eigen::Vector3d& axis, double& acc, double limit) {
          const double k_axis = axis.dot(c * axis);
          if (!(k_axis > 0.0)) return;
          const double old_acc = acc;
          acc = std::clamp(old_acc - axis.dot(rotation()) / k_axis, -limit, limit);
          const Eigen::Vector3d angular = (acc - old_acc) * axis;
          dtheta[r.b] += inverse_inertia[r.b] * angular;
          if (r.a >= 0) dtheta[r.a] -= inverse_inertia[r.a] * angular;
        };
        // Rolling: each tangential axis within l_r lambda_n (a box, not the disk: prototype).
        turn(r.t1, r.couple.x(), r.rolling_m * r.lambda_n);
        turn(r.t2, r.couple.y(), r.rolling_m * r.lambda_n);
        turn(r.normal, r.couple.z(), r.spinning_m * r.lambda_n);
      }
    }
    // Converged when a sweep no longer moves any member (its translation, and its rotation times
    // its contacts' lever): the impulses may still drift where contacts are redundant.
    double moved = 0.0;
    for (std::size_t i = 0; i < dx.size(); ++i) {
      moved = std::max({moved, (dx[i] - previous_dx[i]).norm(),
                        (dtheta[i] - previous_dtheta[i]).norm() * lever[i]});
    }
    previous_dx = dx;
    previous_dtheta = dtheta;
    if (moved <= kJointTolerance * scale) break;
  }
  return it;
}

}  // namespace virtual_go::nonsmooth_island_detail

namespace virtual_go {

int NonsmoothIsland::velocities_jointly(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc,
                                        const std::vector<PairContact>& pairs, bool commit) {
  const std::size_t n = s.size();
  using nonsmooth_island_detail::SolveRow;
  std::vector<double> inverse_mass(n, 0.0);
  std::vector<Eigen::Matrix3d> inverse_inertia(n, Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> dv(n, Eigen::Vector3d::Zero()), dw(n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i]) continue;
    const MotionModel& model = members_[i].setup.model;
    inverse_mass[i] = 1.0 / model.mass_properties().mass();
    inverse_inertia[i] = model.inertia_world(s[i].orientation).inverse();
  }
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
  const int sweeps =
      nonsmooth_island_detail::solve_rows(rows, inverse_mass, inverse_inertia, dv, dw);
  if (commit) nonsmooth_island_detail::store_warm(rows, warm_velocities_);
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
