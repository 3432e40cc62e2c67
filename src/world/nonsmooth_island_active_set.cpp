// The active-set step of the joint solve (nonsmooth_island_impl.h, solve_rows in
// nonsmooth_island_joint.cpp).
#include <Eigen/LU>
#include <Eigen/QR>
#include <array>
#include <cmath>
#include <vector>

#include "nonsmooth_island_impl.h"

namespace virtual_go::nonsmooth_island_detail {
namespace {

// The active-set step (solve_rows). The sweeps alone converge at 0.995 per sweep in the wedges of
// leaning stones (the cluster of benchmark/many: 955 of 23,555 solves capped at 1,000 sweeps, 54 %
// of all sweeps, every other conjugate-gradient step restarted). The step takes from the sweeps'
// impulses which contacts press, which stick, which slide (and along which direction) and which
// couples are at their bounds, and solves for the impulses that make every pressing, sticking and
// free component exact at once (one linear solve, least squares where contacts are redundant). A
// primal active-set method: where an impulse would leave its cone it stops there and that component
// goes to its bound; where a sliding contact would slip along its friction, or a bound couple turn
// with it, or a contact apart approach, it is set free again; a few rounds. The answer is still a
// sweep's, as the sweeps after it project it onto the cones, and solve_rows goes back where the
// step made things worse. Dense: for islands of at most kActiveSetMembers members (a dense solve of
// larger ones costs more than the sweeps it saves).
constexpr std::size_t kActiveSetMembers = 24;
constexpr int kActiveSetRounds = 8;
// Strictly inside a bound by this fraction of it: free; else at the bound.
constexpr double kInside = 1.0 - 1e-9;

// A row's part in the active-set step.
struct RowSet {
  bool pressing = false;
  bool sticking = false;
  std::array<bool, 3> couple_free{};
  Eigen::Vector3d bound = Eigen::Vector3d::Zero();  // bound couples / lambda_n
};

RowSet classify(const SolveRow& r) {
  RowSet set;
  if (!(r.lambda_n > 0.0)) return set;
  set.pressing = true;
  const Eigen::Vector2d lt(r.lambda_1, r.lambda_2);
  set.sticking = lt.norm() < kInside * r.mu * r.lambda_n;
  for (int c = 0; has_couples(r) && c < 3; ++c) {
    if (std::abs(r.couple[c]) < kInside * couple_arm(r, c + 3) * r.lambda_n) {
      set.couple_free[static_cast<std::size_t>(c)] = true;
    } else {
      set.bound[c] = r.couple[c] / r.lambda_n;
    }
  }
  return set;
}

// An unknown's column: what a unit impulse in it does to its (at most two) members' motions (6
// each: translation, rotation), and what its component measures there. Sparse, as each touches
// two members: the system is built member by member.
struct Column {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  int member[2] = {-1, -1};  // compact: b, then a (-1: a fixed body)
  Vector6d effect[2] = {Vector6d::Zero(), Vector6d::Zero()};
  Vector6d measure[2] = {Vector6d::Zero(), Vector6d::Zero()};
};

// Adds to `column` row r's component j: its effect times `weight`, and (with `measure`) sets its
// measure.
void add_column(const SolveRow& r, int j, double weight, Column& column, bool measure) {
  const double sign[2] = {1.0, -1.0};
  for (int side = 0; side < 2; ++side) {
    if (column.member[side] < 0) continue;
    const bool b = side == 0;
    Column::Vector6d& effect = column.effect[side];
    Column::Vector6d& measured = column.measure[side];
    if (j < 3) {
      effect.head<3>() +=
          sign[side] * weight * (b ? r.inverse_mass_b : r.inverse_mass_a) * r.axis(j);
      effect.tail<3>() += sign[side] * weight * (b ? r.turn_b[j] : r.turn_a[j]);
      if (measure) {
        measured.head<3>() = sign[side] * r.axis(j);
        measured.tail<3>() = sign[side] * (b ? r.arm_b[j] : r.arm_a[j]);
      }
    } else {
      effect.tail<3>() +=
          sign[side] * weight * (b ? r.couple_turn_b[j - 3] : r.couple_turn_a[j - 3]);
      if (measure) measured.tail<3>() = sign[side] * r.couple_axis(j - 3);
    }
  }
}

// Sets row r's impulse in component j to `value`, and the members' motions with it.
void set_applied(SolveRow& r, int j, double value, const Motions& m) {
  apply(r, j, value - impulse(r, j), m);
  set_impulse(r, j, value);
}

// The largest a in [0, 1] with f(a) <= 0 for f convex on [0, 1], f(0) <= 0 (bisection).
template <typename F>
double feasible_to(const F& f) {
  if (f(1.0) <= 0.0) return 1.0;
  double low = 0.0, high = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (f(mid) <= 0.0 ? low : high) = mid;
  }
  return low;
}

}  // namespace

bool active_set_step(std::vector<SolveRow>& rows, const Motions& m, double scale) {
  std::vector<int> slot(m.dx.size(), -1);
  int members = 0;
  for (const SolveRow& r : rows) {
    for (const int i : {r.b, r.a}) {
      if (i >= 0 && slot[static_cast<std::size_t>(i)] < 0)
        slot[static_cast<std::size_t>(i)] = members++;
    }
  }
  if (members == 0 || static_cast<std::size_t>(members) > kActiveSetMembers) return false;
  std::vector<RowSet> sets(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) sets[i] = classify(rows[i]);
  const double tolerance = kJointTolerance * scale;
  for (int round = 0; round < kActiveSetRounds; ++round) {
    struct Unknown {
      std::size_t row;
      int component;  // 0: the normal, carrying its row's bound couples
    };
    std::vector<Unknown> unknowns;
    std::vector<int> first(rows.size(), -1);  // each row's normal unknown (its tangents follow)
    for (std::size_t i = 0; i < rows.size(); ++i) {
      RowSet& set = sets[i];
      if (!set.pressing) continue;
      if (!set.sticking && rows[i].mu > 0.0 &&
          Eigen::Vector2d(component(rows[i], 1, m), component(rows[i], 2, m)).norm() <= tolerance) {
        set.sticking = true;  // no slip to give friction a direction: the cone decides
      }
      first[i] = static_cast<int>(unknowns.size());
      unknowns.push_back({i, 0});
      if (rows[i].mu > 0.0) {
        unknowns.push_back({i, 1});
        unknowns.push_back({i, 2});
      }
      for (int c = 0; c < 3; ++c) {
        if (set.couple_free[static_cast<std::size_t>(c)]) unknowns.push_back({i, 3 + c});
      }
    }
    const int k = static_cast<int>(unknowns.size());
    if (k == 0) return round > 0;
    std::vector<Column> columns(static_cast<std::size_t>(k));
    std::vector<std::vector<std::pair<int, int>>> touching(static_cast<std::size_t>(members));
    Eigen::VectorXd residual(k);
    for (int u = 0; u < k; ++u) {
      const std::size_t i = unknowns[static_cast<std::size_t>(u)].row;
      const int j = unknowns[static_cast<std::size_t>(u)].component;
      const SolveRow& r = rows[i];
      Column& column = columns[static_cast<std::size_t>(u)];
      column.member[0] = slot[static_cast<std::size_t>(r.b)];
      column.member[1] = r.a >= 0 ? slot[static_cast<std::size_t>(r.a)] : -1;
      add_column(r, j, 1.0, column, true);
      if (j == 0) {
        for (int c = 0; c < 3; ++c) {
          if (sets[i].bound[c] != 0.0) add_column(r, 3 + c, sets[i].bound[c], column, false);
        }
      }
      for (int side = 0; side < 2; ++side) {
        if (column.member[side] >= 0) {
          touching[static_cast<std::size_t>(column.member[side])].push_back({u, side});
        }
      }
      residual(u) = (j == 0 ? r.target_n : 0.0) - component(r, j, m);
    }
    // system(u, v): what unknown v's unit impulse does to unknown u's component.
    Eigen::MatrixXd system = Eigen::MatrixXd::Zero(k, k);
    for (const auto& list : touching) {
      for (const auto& [u, su] : list) {
        for (const auto& [v, sv] : list) {
          system(u, v) += columns[static_cast<std::size_t>(u)].measure[su].dot(
              columns[static_cast<std::size_t>(v)].effect[sv]);
        }
      }
    }
    // A sliding row's tangents: Coulomb's law F = lambda_t + mu lambda_n u_t / |u_t| = 0 (the
    // friction on the cone, against the slip after it), linearised: a semismooth Newton step.
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!sets[i].pressing || sets[i].sticking || !(rows[i].mu > 0.0)) continue;
      const SolveRow& r = rows[i];
      const int n = first[i], t = n + 1;
      const Eigen::Vector2d slip(component(r, 1, m), component(r, 2, m));
      const Eigen::Vector2d along = slip / slip.norm();
      const Eigen::Matrix2d turn = (r.mu * r.lambda_n / slip.norm()) *
                                   (Eigen::Matrix2d::Identity() - along * along.transpose());
      const Eigen::MatrixXd slip_rows = system.middleRows(t, 2);
      system.middleRows(t, 2) = turn * slip_rows;
      system(t, t) += 1.0;
      system(t + 1, t + 1) += 1.0;
      system.block(t, n, 2, 1) += r.mu * along;
      residual.segment<2>(t) =
          -(Eigen::Vector2d(r.lambda_1, r.lambda_2) + r.mu * r.lambda_n * along);
    }
    // LU first (most systems are regular); least squares where redundant contacts make it
    // singular, which LU's residual shows.
    Eigen::VectorXd step = system.partialPivLu().solve(residual);
    if (!step.allFinite() || (system * step - residual).norm() > 1e-9 * residual.norm()) {
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solver(system);
      solver.setThreshold(1e-10);
      step = solver.solve(residual);
    }
    if (!step.allFinite()) return round > 0;
    // How far along the step every impulse stays within its bounds.
    std::vector<double> step_of(rows.size() * kComponents, 0.0);
    for (int u = 0; u < k; ++u) {
      step_of[unknowns[static_cast<std::size_t>(u)].row * kComponents +
              static_cast<std::size_t>(unknowns[static_cast<std::size_t>(u)].component)] = step(u);
    }
    double alpha = 1.0;
    std::size_t blocked_row = rows.size();
    int blocked_component = -1;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!sets[i].pressing) continue;
      const SolveRow& r = rows[i];
      const double* d = &step_of[i * kComponents];
      const double n0 = r.lambda_n, dn = d[0];
      const auto block = [&](double a, int component) {
        if (a < alpha) {
          alpha = a;
          blocked_row = i;
          blocked_component = component;
        }
      };
      if (dn < 0.0) block(std::max(0.0, -n0 / dn), 0);
      if (sets[i].sticking && r.mu > 0.0) {
        const Eigen::Vector2d t0(r.lambda_1, r.lambda_2), dt(d[1], d[2]);
        block(feasible_to([&](double a) { return (t0 + a * dt).norm() - r.mu * (n0 + a * dn); }),
              1);
      }
      for (int c = 0; c < 3; ++c) {
        if (!sets[i].couple_free[static_cast<std::size_t>(c)]) continue;
        const double arm = couple_arm(r, c + 3);
        block(feasible_to([&](double a) {
                return std::abs(r.couple[c] + a * d[3 + c]) - arm * (n0 + a * dn);
              }),
              3 + c);
      }
    }
    for (int u = 0; u < k; ++u) {
      const std::size_t i = unknowns[static_cast<std::size_t>(u)].row;
      const int j = unknowns[static_cast<std::size_t>(u)].component;
      SolveRow& r = rows[i];
      const double delta = alpha * step(u);
      set_impulse(r, j, impulse(r, j) + delta);
      if (j == 0) r.couple += sets[i].bound * delta;
    }
    std::vector<Column::Vector6d> motion(static_cast<std::size_t>(members),
                                         Column::Vector6d::Zero());
    for (int u = 0; u < k; ++u) {
      const Column& column = columns[static_cast<std::size_t>(u)];
      for (int side = 0; side < 2; ++side) {
        if (column.member[side] >= 0) {
          motion[static_cast<std::size_t>(column.member[side])] +=
              alpha * step(u) * column.effect[side];
        }
      }
    }
    for (std::size_t i = 0; i < slot.size(); ++i) {
      if (slot[i] < 0) continue;
      m.dx[i] += motion[static_cast<std::size_t>(slot[i])].head<3>();
      m.dtheta[i] += motion[static_cast<std::size_t>(slot[i])].tail<3>();
    }
    if (blocked_component >= 0) {
      // The component that stopped the step goes to its bound, exactly.
      SolveRow& r = rows[blocked_row];
      RowSet& set = sets[blocked_row];
      if (blocked_component == 0) {
        for (int j = 0; j < kComponents; ++j) set_applied(r, j, 0.0, m);
        set = RowSet{};
      } else if (blocked_component == 1) {
        const Eigen::Vector2d lt(r.lambda_1, r.lambda_2);
        if (lt.norm() > 0.0) {
          const Eigen::Vector2d on = lt * (r.mu * r.lambda_n / lt.norm());
          set_applied(r, 1, on.x(), m);
          set_applied(r, 2, on.y(), m);
        }
        set.sticking = false;
      } else {
        // Its ratio to the normal is the arm itself (a row that has just started to press has
        // lambda_n = 0: the couple over it would be 0 / 0).
        const int c = blocked_component - 3;
        const double arm = r.couple[c] < 0.0 ? -couple_arm(r, blocked_component)
                                             : couple_arm(r, blocked_component);
        set_applied(r, blocked_component, arm * r.lambda_n, m);
        set.couple_free[static_cast<std::size_t>(c)] = false;
        set.bound[c] = arm;
      }
      continue;
    }
    // The whole step taken: free again what moves against its bound, and another Newton round
    // where a sliding friction is not yet against its slip.
    bool changed = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      SolveRow& r = rows[i];
      RowSet& set = sets[i];
      if (!set.pressing) {
        if (component(r, 0, m) < r.target_n - tolerance) {
          set.pressing = true;
          set.sticking = true;
          for (int c = 0; has_couples(r) && c < 3; ++c) {
            set.couple_free[static_cast<std::size_t>(c)] = true;
          }
          changed = true;
        }
        continue;
      }
      if (!set.sticking && r.mu > 0.0) {
        const Eigen::Vector2d slip(component(r, 1, m), component(r, 2, m));
        const Eigen::Vector2d lt(r.lambda_1, r.lambda_2);
        if (slip.norm() <= tolerance || slip.dot(lt) > 0.0) {
          set.sticking = true;
          changed = true;
        } else if ((lt + r.mu * r.lambda_n * slip / slip.norm()).norm() >
                   1e-12 * r.mu * r.lambda_n) {
          changed = true;
        }
      }
      for (int c = 0; c < 3; ++c) {
        if (set.couple_free[static_cast<std::size_t>(c)] || set.bound[c] == 0.0) continue;
        const double turn = component(r, 3 + c, m);
        if (std::abs(turn) > tolerance && turn * set.bound[c] > 0.0) {
          set.couple_free[static_cast<std::size_t>(c)] = true;
          set.bound[c] = 0.0;
          changed = true;
        }
      }
    }
    if (!changed) return true;
  }
  return true;
}

// Whether the active-set step costs less than the sweeps still to go at the rate of the last
// kActiveSetEvery (`history`: each sweep's largest motion; `tolerance`: the last one's bound). The
// step's dense LU costs about k^3 / 90 sweeps over the rows for k unknowns (2.5 rounds of 2/3 k^3
// against 150 per row and sweep: measured in benchmark/many, where the steps with 15 members
// and 20 rows cost more than the sweeps they saved).
bool active_set_pays(const std::vector<SolveRow>& rows, const std::vector<double>& history,
                     double tolerance) {
  if (history.size() <= static_cast<std::size_t>(kActiveSetEvery)) return false;
  double unknowns = 0.0;
  for (const SolveRow& r : rows) {
    if (r.lambda_n > 0.0) unknowns += 1.0 + (r.mu > 0.0 ? 2.0 : 0.0) + (has_couples(r) ? 3.0 : 0.0);
  }
  const double step_in_sweeps =
      unknowns * unknowns * unknowns / (90.0 * static_cast<double>(rows.size()));
  const double now = history.back(), before = history[history.size() - 1 - kActiveSetEvery];
  if (!(now > tolerance)) return false;
  const double rate = std::pow(now / before, 1.0 / kActiveSetEvery);
  if (!(rate < 1.0)) return true;  // not converging
  return std::log(tolerance / now) / std::log(rate) > step_in_sweeps;
}

}  // namespace virtual_go::nonsmooth_island_detail
