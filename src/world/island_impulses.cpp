#include "virtual_go/world/island_impulses.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace virtual_go {

Eigen::Matrix3d contact_compliance(double mass_kg, const Eigen::Matrix3d& inverse_inertia_world,
                                   const Eigen::Vector3d& lever_arm_world) {
  const Eigen::Vector3d& r = lever_arm_world;
  Eigen::Matrix3d rx;
  rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return Eigen::Matrix3d::Identity() / mass_kg - rx * inverse_inertia_world * rx;
}

bool may_slip(const Eigen::Vector3d& n, const Eigen::Vector3d& u,
              const Eigen::Vector3d& accumulated, double mu, double slip_tolerance_mps) {
  const Eigen::Vector3d u_t = u - u.dot(n) * n;
  return mu > 0.0 && accumulated.dot(n) > 0.0 && u_t.norm() > slip_tolerance_mps;
}

Eigen::Vector3d friction_impulse(const Eigen::Vector3d& n, const Eigen::Matrix3d& k,
                                 const Eigen::Vector3d& u, const Eigen::Vector3d& accumulated,
                                 double mu, double slip_tolerance_mps) {
  if (!may_slip(n, u, accumulated, mu, slip_tolerance_mps)) return Eigen::Vector3d::Zero();
  const double normal_ns = accumulated.dot(n);
  const Eigen::Vector3d u_t = u - u.dot(n) * n;
  const Eigen::Vector3d t1 = u_t.normalized(), t2 = n.cross(t1);
  Eigen::Matrix<double, 3, 2> basis;
  basis << t1, t2;
  const Eigen::Matrix2d k_tt = basis.transpose() * k * basis;
  const Eigen::Vector2d p2 = -k_tt.ldlt().solve(basis.transpose() * u_t);
  const Eigen::Vector3d p_t = basis * p2;
  const Eigen::Vector3d t_sum = accumulated - normal_ns * n;
  const double limit = mu * normal_ns;
  // Largest alpha in [0, 1] with |t_sum + alpha p_t| <= limit.
  const double a = p_t.squaredNorm(), b = 2.0 * t_sum.dot(p_t),
               c = t_sum.squaredNorm() - limit * limit;
  if (!(a > 0.0) || c > 0.0) return Eigen::Vector3d::Zero();
  const double alpha = std::min(1.0, (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a));
  if (!(alpha > 0.0)) return Eigen::Vector3d::Zero();
  return alpha * p_t;
}

void SweepCompliances::reset(std::size_t members, std::size_t pairs) {
  members_.assign(members, MemberEntry{});
  board_.assign(2 * members, ContactEntry{});
  pair_.assign(pairs, ContactEntry{});
}

const SweepCompliances::MemberEntry& SweepCompliances::member(std::size_t i,
                                                              const MotionModel& model,
                                                              const RigidBodyState& s) {
  MemberEntry& m = members_[i];
  // The sweeps change velocities only (every impulse, the held stone's and the obstacles'
  // included, is applied to v and L), so a member's pose is the one its entry was made at.
  assert(!m.ready || m.position_world == s.position_world);
  if (!m.ready) {
    m.position_world = s.position_world;
    m.inverse_inertia_world = model.inertia_world(s.orientation).inverse();
    m.ready = true;
  }
  return m;
}

Eigen::Matrix3d SweepCompliances::compliance(const MemberEntry& m, const MotionModel& model,
                                             const Eigen::Vector3d& point_world) const {
  return contact_compliance(model.mass_properties().mass(), m.inverse_inertia_world,
                            point_world - m.position_world);
}

const Eigen::Matrix3d& SweepCompliances::board(std::size_t i, int k, const MotionModel& model,
                                               const RigidBodyState& s,
                                               const Eigen::Vector3d& point_world) {
  ContactEntry& c = board_[2 * i + static_cast<std::size_t>(k)];
  if (!c.ready) {
    c.k = compliance(member(i, model, s), model, point_world);
    c.ready = true;
  }
  return c.k;
}

Eigen::Vector3d SweepCompliances::point_velocity(std::size_t i, const MotionModel& model,
                                                 const RigidBodyState& s,
                                                 const Eigen::Vector3d& point_world) {
  const Eigen::Vector3d omega_world =
      member(i, model, s).inverse_inertia_world * s.angular_momentum_world;
  return s.velocity_world + omega_world.cross(point_world - s.position_world);
}

Eigen::Matrix3d SweepCompliances::member_at(std::size_t i, const MotionModel& model,
                                            const RigidBodyState& s,
                                            const Eigen::Vector3d& point_world) {
  return compliance(member(i, model, s), model, point_world);
}

const Eigen::Matrix3d& SweepCompliances::pair(std::size_t j, std::size_t a,
                                              const MotionModel& model_a, const RigidBodyState& s_a,
                                              std::size_t b, const MotionModel& model_b,
                                              const RigidBodyState& s_b,
                                              const Eigen::Vector3d& point_world) {
  ContactEntry& c = pair_[j];
  if (!c.ready) {
    c.k = compliance(member(a, model_a, s_a), model_a, point_world) +
          compliance(member(b, model_b, s_b), model_b, point_world);
    c.ready = true;
  }
  return c.k;
}

}  // namespace virtual_go
