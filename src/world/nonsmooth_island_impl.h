// Inside NonsmoothIsland (nonsmooth_island.h): the pieces more than one of its rooms uses. Rooms:
//   nonsmooth_island.cpp           options, construction, the lattice driver and the members' ends
//   nonsmooth_island_energy.cpp    the energy guard and a free island's conserved totals
//   nonsmooth_island_contacts.cpp  contact detection and the position corrections (step 2)
//   nonsmooth_island_sub_step.cpp  one sub-step and its velocity stage (step 3)
//   nonsmooth_island_joint.cpp     the joint solve (NonsmoothContactOptions::joint_solve)
//   nonsmooth_island_active_set.cpp  its active-set step
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/go/board_distance.h"

namespace virtual_go::nonsmooth_island_detail {

// One contact of the joint solve (NonsmoothContactOptions::joint_solve), for the positions
// (u0 = 0, target_n the depth to remove, m) or the velocities (u0 the contact's relative velocity,
// target_n = 0, m/s). Impulses are kg m or N s accordingly.
struct SolveRow {
  int a = -1, b = 0;  // a = -1: a fixed body (the board, the table, an obstacle)
  long key = 0;       // the contact's name for the warm start
  Eigen::Vector3d normal, ra, rb, t1, t2;
  Eigen::Vector3d u0 = Eigen::Vector3d::Zero();  // the contact's relative motion before the solve
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();  // the relative rotation (rate) before the solve
  double target_n = 0.0;                         // wanted normal part, at least
  double mu = 0.0;
  double rolling_m = 0.0, spinning_m = 0.0;          // couples at most l_r and l_s times the normal
  double lambda_n = 0, lambda_1 = 0, lambda_2 = 0;   // accumulated
  Eigen::Vector3d couple = Eigen::Vector3d::Zero();  // accumulated angular impulse (t1, t2, n)
  // What every iteration needs, computed once by make_row (the solve's cost is its iterations):
  // per axis j of (n, t1, t2), each body's arm r x axis_j (a motion's part along axis_j from a
  // rotation is its dot with the arm) and the rotation I^-1 (r x axis_j) a unit impulse along
  // axis_j gives; per couple axis c of (t1, t2, n), the rotation I^-1 axis_c a unit couple gives
  // and the inverse of the pair's compliance about it; the inverse masses; the normal's inverse
  // compliance, the tangential block's, its inverse and eigen-decomposition. Zero for a fixed a.
  Eigen::Vector3d arm_b[3], arm_a[3], turn_b[3], turn_a[3], couple_turn_b[3], couple_turn_a[3];
  double inverse_mass_b = 0.0, inverse_mass_a = 0.0;
  double inverse_k_n = 0.0;
  Eigen::Matrix2d k_t = Eigen::Matrix2d::Zero(), inverse_k_t = Eigen::Matrix2d::Zero();
  Eigen::Vector2d k_t_values = Eigen::Vector2d::Zero();  // k_t = basis diag(values) basis^T
  Eigen::Matrix2d k_t_basis = Eigen::Matrix2d::Identity();
  double inverse_couple_k[3] = {0.0, 0.0, 0.0};
  Eigen::Vector3d u0_axes, w0_axes;  // u0 along (n, t1, t2) and w0 about (t1, t2, n): by solve_rows
  const Eigen::Vector3d& axis(int j) const { return j == 0 ? normal : j == 1 ? t1 : t2; }
  const Eigen::Vector3d& couple_axis(int c) const { return c == 0 ? t1 : c == 1 ? t2 : normal; }
};
// A row at `point_world` between members a (-1: a fixed body) and b of `states`, with its axes
// and its compliance (u0, target_n and the couples left to the caller).
SolveRow make_row(int a, int b, const Eigen::Vector3d& normal_world,
                  const Eigen::Vector3d& point_world, double mu,
                  const std::vector<RigidBodyState>& states,
                  const std::vector<double>& inverse_mass,
                  const std::vector<Eigen::Matrix3d>& inverse_inertia);

// Each row's impulses from `warm` (by key), expressed in its own axes; and back.
template <typename Warm>
void load_warm(std::vector<SolveRow>& rows, const Warm& warm) {
  for (SolveRow& r : rows) {
    const auto found = warm.find(r.key);
    if (found == warm.end()) continue;
    const Eigen::Vector3d& p = found->second.impulse_world;
    const Eigen::Vector3d& c = found->second.couple_world;
    r.lambda_n = std::max(0.0, p.dot(r.normal));
    r.lambda_1 = p.dot(r.t1);
    r.lambda_2 = p.dot(r.t2);
    r.couple = Eigen::Vector3d(c.dot(r.t1), c.dot(r.t2), c.dot(r.normal));
  }
}
template <typename Warm>
void store_warm(const std::vector<SolveRow>& rows, Warm& warm) {
  warm.clear();
  for (const SolveRow& r : rows) {
    auto& w = warm[r.key];
    w.impulse_world = r.lambda_n * r.normal + r.lambda_1 * r.t1 + r.lambda_2 * r.t2;
    w.couple_world = r.couple.x() * r.t1 + r.couple.y() * r.t2 + r.couple.z() * r.normal;
  }
}

// The largest motion of a member over an iteration (relative to the scale, solve_rows) below
// which a solve stops (at kMaxJointIterations at the latest).
constexpr double kJointTolerance = 1e-9;

// A row's six components: 0 the normal, 1 and 2 the tangents (impulses, motions along the axes),
// 3 to 5 the couples about t1, t2 and the normal (angular impulses, rotations about them).
constexpr int kComponents = 6;

// The members' motions (translation or velocity, rotation or angular velocity) from the solve.
struct Motions {
  std::vector<Eigen::Vector3d>& dx;
  std::vector<Eigen::Vector3d>& dtheta;
};

// Row r's relative motion in component j (b against a). Inlined: it is most of an iteration.
[[gnu::always_inline]] inline double component(const SolveRow& r, int j, const Motions& m) {
  if (j < 3) {
    double u = r.axis(j).dot(m.dx[r.b]) + r.arm_b[j].dot(m.dtheta[r.b]);
    if (r.a >= 0) u -= r.axis(j).dot(m.dx[r.a]) + r.arm_a[j].dot(m.dtheta[r.a]);
    return u + r.u0_axes[j];
  }
  const Eigen::Vector3d& axis = r.couple_axis(j - 3);
  double w = axis.dot(m.dtheta[r.b]);
  if (r.a >= 0) w -= axis.dot(m.dtheta[r.a]);
  return w + r.w0_axes[j - 3];
}

// An impulse p in row r's component j, on b and (opposite) on a. Inlined as component() is.
[[gnu::always_inline]] inline void apply(const SolveRow& r, int j, double p, const Motions& m) {
  if (j < 3) {
    m.dx[r.b] += (r.inverse_mass_b * p) * r.axis(j);
    m.dtheta[r.b] += p * r.turn_b[j];
    if (r.a >= 0) {
      m.dx[r.a] -= (r.inverse_mass_a * p) * r.axis(j);
      m.dtheta[r.a] -= p * r.turn_a[j];
    }
    return;
  }
  m.dtheta[r.b] += p * r.couple_turn_b[j - 3];
  if (r.a >= 0) m.dtheta[r.a] -= p * r.couple_turn_a[j - 3];
}

// Row r's accumulated impulse in component j.
inline double impulse(const SolveRow& r, int j) {
  return j == 0 ? r.lambda_n : j == 1 ? r.lambda_1 : j == 2 ? r.lambda_2 : r.couple[j - 3];
}
inline void set_impulse(SolveRow& r, int j, double value) {
  (j == 0 ? r.lambda_n : j == 1 ? r.lambda_1 : j == 2 ? r.lambda_2 : r.couple[j - 3]) = value;
}
// The largest couple in component j (3 to 5) per unit normal impulse.
inline double couple_arm(const SolveRow& r, int j) { return j < 5 ? r.rolling_m : r.spinning_m; }
// Whether row r has rolling or spinning couples at all (board rows; pair rows have none).
inline bool has_couples(const SolveRow& r) { return r.rolling_m > 0.0 || r.spinning_m > 0.0; }

// The active-set step of solve_rows (nonsmooth_island_active_set.cpp): from the contact states the
// sweeps reached, the impulses that make them exact at once. False (nothing changed) where it does
// not apply. active_set_pays: whether it costs less than the sweeps still to go, from each sweep's
// largest motion so far (`history`) and the solve's bound on it (`tolerance`).
constexpr int kFirstActiveSetStep = 20;  // sweeps before the first step (most solves end before)
constexpr int kActiveSetEvery = 10;      // sweeps between steps
bool active_set_step(std::vector<SolveRow>& rows, const Motions& m, double scale);
bool active_set_pays(const std::vector<SolveRow>& rows, const std::vector<double>& history,
                     double tolerance);

// Projected Gauss-Seidel with accumulated impulses (each clamped as a whole: the normal at >= 0,
// the tangential within mu lambda_n, each couple within l lambda_n), so that a later contact can
// take back what an earlier one pushed: it converges to the joint answer, not a feasible point
// above it (pushes only can lift an island above its start); accelerated by nonsmooth nonlinear
// conjugate gradients (the sweeps' fixed points, each answer a sweep's). dx, dtheta: each member's
// motion (translation and rotation, or velocity and angular velocity) from the solve. Returns the
// iterations (sweeps over the rows) it took. It stops when a sweep moves no member by more than
// 1e-9 of the scale: the largest of `scale`, the rows' targets and their contacts' speeds. Where
// the sweeps converge slowly it takes active-set steps (nonsmooth_island_joint.cpp; off with
// `active_set_steps` false, for the tests' comparison).
constexpr int kMaxJointIterations = 1000;  // per solve
int solve_rows(std::vector<SolveRow>& rows, std::vector<Eigen::Vector3d>& dx,
               std::vector<Eigen::Vector3d>& dtheta, double scale = 0.0,
               bool active_set_steps = true);

inline bool apart_by_bounds(const BoardDistance& a, const RigidBodyState& sa,
                            const BoardDistance& b, const RigidBodyState& sb, double margin_m) {
  // A lens lies within the sphere of its rim radius about its centre.
  const double reach = a.lens().half_width() + b.lens().half_width() + margin_m;
  return (sb.position_world - sa.position_world).squaredNorm() > reach * reach;
}

}  // namespace virtual_go::nonsmooth_island_detail
