// Inside NonsmoothIsland (nonsmooth_island.h): the pieces more than one of its rooms uses. Rooms:
//   nonsmooth_island.cpp           options, construction, the lattice driver and the members' ends
//   nonsmooth_island_energy.cpp    the energy guard and a free island's conserved totals
//   nonsmooth_island_contacts.cpp  contact detection and the position corrections (step 2)
//   nonsmooth_island_sub_step.cpp  one sub-step and its velocity stage (step 3)
//   nonsmooth_island_joint.cpp     the joint solve (NonsmoothContactOptions::joint_solve)
#pragma once

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
  Eigen::Matrix3d k;                                 // compliance in (n, t1, t2)
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

// Projected Gauss-Seidel with accumulated impulses (each clamped as a whole: the normal at >= 0,
// the tangential within mu lambda_n, each couple within l lambda_n), so that a later contact can
// take back what an earlier one pushed: it converges to the joint answer, not a feasible point
// above it (pushes only can lift an island above its start). dx, dtheta: each member's motion
// (translation and rotation, or velocity and angular velocity) from the solve. Returns the
// iterations (sweeps over the rows) it took.
int solve_rows(std::vector<SolveRow>& rows, const std::vector<double>& inverse_mass,
               const std::vector<Eigen::Matrix3d>& inverse_inertia,
               std::vector<Eigen::Vector3d>& dx, std::vector<Eigen::Vector3d>& dtheta);

inline bool apart_by_bounds(const BoardDistance& a, const RigidBodyState& sa,
                            const BoardDistance& b, const RigidBodyState& sb, double margin_m) {
  // A lens lies within the sphere of its rim radius about its centre.
  const double reach = a.lens().half_width() + b.lens().half_width() + margin_m;
  return (sb.position_world - sa.position_world).squaredNorm() > reach * reach;
}

}  // namespace virtual_go::nonsmooth_island_detail
