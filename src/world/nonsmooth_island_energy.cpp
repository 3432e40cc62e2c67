// NonsmoothIsland's energy guard (the island's energy, its rigid motion, the scaling of the
// motion beyond it) and a free island's conserved totals (momentum and angular momentum kept to
// their closed forms from the anchor).
#include <cmath>
#include <limits>
#include <optional>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace virtual_go {
namespace {

// The largest factor by which scale_kinetic_energy grows the motion beyond the kept rigid
// motion (a sample whose partial sub-step lost more energy than the whole sub-step).
constexpr double kLargestGrowth = 2.0;

}  // namespace

double NonsmoothIsland::member_energy(std::size_t i, const RigidBodyState& s) const {
  return body_energy(members_[i].setup.model, s, members_[i].setup.gravity_world);
}

double NonsmoothIsland::energy(const std::vector<RigidBodyState>& s,
                               const std::vector<char>& active, double* round_off_j) const {
  // The energy is a sum of terms (potential -m g . x about the world origin, kinetic), each
  // exact to an ulp or so: 16 epsilon of the sum of their magnitudes bounds its round-off.
  double e = 0.0, magnitude = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!active[i]) continue;
    const double e_i = member_energy(i, s[i]);
    e += e_i;
    if (round_off_j) {
      const double p = member_potential(i, s[i]);
      magnitude += std::abs(p) + std::abs(e_i - p);
    }
  }
  if (round_off_j) *round_off_j = 16.0 * std::numeric_limits<double>::epsilon() * magnitude;
  return e;
}

double NonsmoothIsland::member_potential(std::size_t i, const RigidBodyState& s) const {
  return body_potential_energy(members_[i].setup.model.mass_properties().mass(), s.position_world,
                               members_[i].setup.gravity_world);
}

double NonsmoothIsland::potential(const std::vector<RigidBodyState>& s,
                                  const std::vector<char>& active) const {
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (active[i]) e += member_potential(i, s[i]);
  }
  return e;
}

NonsmoothIsland::RigidMotion NonsmoothIsland::rigid_motion(const std::vector<RigidBodyState>& s,
                                                           Kept kept) const {
  // The island as one rigid body: centre of mass X, velocity V, inertia about X
  // I = sum (I_i + m_i (|r_i|^2 1 - r_i r_i^T)), angular momentum about X L = sum (L_i + m_i r_i x
  // (v_i - V)), Omega = I^-1 L. Each member's share: v_i = V + Omega x r_i, L_i = I_i Omega.
  // The rest of the motion carries no momentum and no angular momentum, and its kinetic energy
  // adds to the rigid motion's (the cross terms are V . sum m dv + Omega . (sum m r x dv + I_i
  // dw) = 0). Horizontal: V's horizontal part and Omega = L_z / I_zz about the vertical; the
  // cross terms are then V_h . (sum m dv)_h + Omega_z (sum m r x dv + I_i dw)_z = 0, the rest
  // carrying no horizontal momentum and no L_z.
  const std::size_t n = s.size();
  double mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), momentum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i]) continue;
    const double m = members_[i].setup.model.mass_properties().mass();
    mass += m;
    centre += m * s[i].position_world;
    momentum += m * s[i].velocity_world;
  }
  centre /= mass;
  Eigen::Vector3d v_centre = momentum / mass;
  const bool horizontal = kept == Kept::horizontal;
  if (horizontal) v_centre.z() = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Vector3d spin = Eigen::Vector3d::Zero();
  std::vector<Eigen::Matrix3d> own(n, Eigen::Matrix3d::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i]) continue;
    const double m = members_[i].setup.model.mass_properties().mass();
    const Eigen::Vector3d r = s[i].position_world - centre;
    own[i] = members_[i].setup.model.inertia_world(s[i].orientation);
    inertia += own[i] + m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    spin += s[i].angular_momentum_world + m * r.cross(s[i].velocity_world - v_centre);
  }
  const Eigen::Vector3d omega = horizontal ? Eigen::Vector3d(0.0, 0.0, spin.z() / inertia(2, 2))
                                           : Eigen::Vector3d(inertia.ldlt().solve(spin));
  RigidMotion rigid;
  rigid.centre_world = centre;
  rigid.inertia_world = inertia;
  rigid.velocity_world.assign(n, Eigen::Vector3d::Zero());
  rigid.angular_momentum_world.assign(n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    if (!lattice_.active[i]) continue;
    rigid.velocity_world[i] = v_centre + omega.cross(s[i].position_world - centre);
    rigid.angular_momentum_world[i] = own[i] * omega;
  }
  return rigid;
}

void NonsmoothIsland::scale_motion(std::vector<RigidBodyState>& s, double factor,
                                   const RigidMotion* rigid) const {
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    if (!rigid) {
      s[i].velocity_world *= factor;
      s[i].angular_momentum_world *= factor;
      continue;
    }
    const Eigen::Vector3d &v = rigid->velocity_world[i], &l = rigid->angular_momentum_world[i];
    s[i].velocity_world = v + factor * (s[i].velocity_world - v);
    s[i].angular_momentum_world = l + factor * (s[i].angular_momentum_world - l);
  }
}

double NonsmoothIsland::energy_round_off(const std::vector<RigidBodyState>& s) const {
  double round_off_j = 0.0;
  energy(s, lattice_.active, &round_off_j);
  return round_off_j;
}

bool NonsmoothIsland::scale_kinetic_energy(std::vector<RigidBodyState>& s, double energy_j,
                                           Kept kept) const {
  // Velocity and angular momentum of all members scaled together: the kinetic energy is
  // quadratic in them, the potential energy and the poses do not change. Keeping totals (only
  // internal forces act on them), the motion relative to the rigid motion that carries them is
  // scaled instead, and that rigid motion is kept.
  std::optional<RigidMotion> rigid;
  double fixed = potential(s, lattice_.active);
  if (kept != Kept::none) {
    rigid = rigid_motion(s, kept);
    std::vector<RigidBodyState> r = s;
    for (std::size_t i = 0; i < r.size(); ++i) {
      r[i].velocity_world = rigid->velocity_world[i];
      r[i].angular_momentum_world = rigid->angular_momentum_world[i];
    }
    fixed = energy(r, lattice_.active);
  }
  const RigidMotion* keep = rigid ? &*rigid : nullptr;
  const double kinetic = energy(s, lattice_.active) - fixed;
  const double target = energy_j - fixed;
  if (!(target >= 0.0) || !(kinetic > 0.0)) return false;
  // The relative motion may grow by a bounded factor only: when it is almost gone (a row moving
  // as one) the factor that grows it to a round-off's worth of energy would be any number.
  if (keep && target > kLargestGrowth * kLargestGrowth * kinetic) return false;
  std::vector<RigidBodyState> scaled = s;
  scale_motion(scaled, std::sqrt(target / kinetic), keep);
  // The scaled energy can come out a few ulps above the target: shrink a little more (never by
  // more than a millionth: beyond round-off the target cannot be reached this way).
  for (double shrink = 1e-15; shrink < 1e-6 && energy(scaled, lattice_.active) > energy_j;
       shrink *= 4.0) {
    scale_motion(scaled, 1.0 - shrink, keep);
  }
  if (!(energy(scaled, lattice_.active) <= energy_j)) return false;
  s = std::move(scaled);
  return true;
}

Eigen::Vector3d NonsmoothIsland::angular_momentum(const std::vector<RigidBodyState>& s) const {
  Eigen::Vector3d l = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    const double m = members_[i].setup.model.mass_properties().mass();
    l += s[i].angular_momentum_world + m * s[i].position_world.cross(s[i].velocity_world);
  }
  return l;
}

void NonsmoothIsland::restore_angular_momentum(std::vector<RigidBodyState>& s,
                                               const Eigen::Vector3d& before) const {
  // A pair correction moves both stones along n with the momentum kept (split by inverse mass),
  // but changes sum m x x v by mu d n x (v_b - v_a). Returned by a rigid rotation of the whole
  // island about its centre of mass (no momentum; energy of its order, which the guard takes).
  const Eigen::Vector3d missing = before - angular_momentum(s);
  if (!(missing.norm() > 0.0)) return;
  const RigidMotion rigid = rigid_motion(s);
  const Eigen::Vector3d d_omega = rigid.inertia_world.ldlt().solve(missing);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    s[i].velocity_world += d_omega.cross(s[i].position_world - rigid.centre_world);
    s[i].angular_momentum_world +=
        members_[i].setup.model.inertia_world(s[i].orientation) * d_omega;
  }
}

NonsmoothIsland::FreeAnchor NonsmoothIsland::anchor_of(const std::vector<RigidBodyState>& s,
                                                       double t_s) const {
  FreeAnchor a;
  a.time_s = t_s;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    const double m = members_[i].setup.model.mass_properties().mass();
    a.mass_kg += m;
    a.momentum_world += m * s[i].velocity_world;
    a.centre_world += m * s[i].position_world;
  }
  a.centre_world /= a.mass_kg;
  a.centre_velocity_world = a.momentum_world / a.mass_kg;
  a.angular_momentum_world = angular_momentum(s);
  return a;
}

void NonsmoothIsland::keep_free_totals(std::vector<RigidBodyState>& s, const FreeAnchor& a,
                                       double t_s) const {
  // Every sub-step re-integrates the members, and its round-off (the flight's v + g h, the
  // impulses' v -/+ P/m, the corrections' split) would add up over the sub-steps as a random
  // walk (measured 1.1e-14 of the momentum over 0.1 s); set against the closed form from the
  // anchor, only one sub-step's round-off is left.
  const double tau = t_s - a.time_s;
  const Eigen::Vector3d& g = members_.front().setup.gravity_world;
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (lattice_.active[i]) {
      momentum += members_[i].setup.model.mass_properties().mass() * s[i].velocity_world;
    }
  }
  const Eigen::Vector3d dv = (a.momentum_world + (a.mass_kg * tau) * g - momentum) / a.mass_kg;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (lattice_.active[i]) s[i].velocity_world += dv;
  }
  restore_angular_momentum(
      s, a.angular_momentum_world +
             a.mass_kg *
                 (tau * a.centre_world + (0.5 * tau * tau) * a.centre_velocity_world).cross(g));
}

}  // namespace virtual_go
