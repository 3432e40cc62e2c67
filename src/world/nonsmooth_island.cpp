#include "virtual_go/world/nonsmooth_island.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/pair_impact.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/geometry/lens_pair_distance.h"
#include "virtual_go/world/island_impulses.h"

namespace virtual_go {
namespace {

// Contact-point normal speeds above -this (m/s) are not approaching: they move a contact by less
// than 1e-16 m in a sub-step.
constexpr double kApproachToleranceMps = 1e-12;
// A position correction moves this much (m) beyond the touching pose, so that the recomputed
// gap, whose round-off is ~1e-17 m, comes out non-negative.
constexpr double kCorrectionSlackM = 1e-15;
// No handed-out state overlaps by more than this (m): gaps are exact to ~1e-17 m.
constexpr double kGapToleranceM = 1e-12;
constexpr int kMaxCorrections = 16;        // per member and sweep, board and table
constexpr int kMaxProjectionSweeps = 100;  // then the touching members keep their poses
// The plane model accepts |u_n| <= 1e-6 m/s; hand over only well inside that.
constexpr double kPlaneNormalSpeedMps = 1e-7;
// A pair correction along n does not move a stone whose board contact normal makes a cosine
// above this with the direction it would be pushed into the board.
constexpr double kBlockedCosine = 1e-6;
// A pair impulse does not move a stone it would press into a board contact it lies on with a
// cosine above this (mostly into the board: a stone under another, not one pushed along a row).
constexpr double kPressedCosine = 0.5;
// ... but only after this many plain sweeps: the first ones pass the impulse through the lower
// stone to the board with its torque (an eccentric landing can tip it); holding the lower stone
// from then on makes the rest converge at once instead of halving per sweep.
constexpr int kPlainSweeps = 8;
// A member leaves the island only with no other member within this many contact margins: the
// World joins stones in contact within one margin (touching, approaching or not), so a member let
// go just beyond one margin would rejoin within a few passes, again and again (a cradle row on
// the real board: 754 islands of ~2 sub-steps each, resting at 2.3 s instead of 0.14 s).
constexpr double kKeepMarginFactor = 10.0;

void apply_impulse(const MotionModel& model, RigidBodyState& s, const Eigen::Vector3d& point_world,
                   const Eigen::Vector3d& impulse_world) {
  s.velocity_world += impulse_world / model.mass_properties().mass();
  s.angular_momentum_world += (point_world - s.position_world).cross(impulse_world);
}

ContactMaterial plastic(ContactMaterial m) {
  m.restitution = 0.0;
  return m;
}

bool apart_by_bounds(const BoardDistance& a, const RigidBodyState& sa, const BoardDistance& b,
                     const RigidBodyState& sb, double margin_m) {
  // A lens lies within the sphere of its rim radius about its centre.
  const double reach = a.lens().half_width() + b.lens().half_width() + margin_m;
  return (sb.position_world - sa.position_world).squaredNorm() > reach * reach;
}

// The contact to push along (lens_pair_distance.h): not a tilted normal of touching rims.
// `best()` gives lens_pair_distance's contact; it is asked for only when the centre line is not
// certain to be the answer (a row at rest: the centre line, without the distance's multistart).
template <typename Best>
LensPairContact pair_contact(const LensGeometry& a, const LensPose& pa, const LensGeometry& b,
                             const LensPose& pb, const Best& best) {
  const CentreLineContact along = lens_pair_centre_line(a, pa, b, pb, kGapToleranceM);
  if (along.certain) return along.contact;
  return lens_pair_push_contact(along, best(), kGapToleranceM);
}

}  // namespace

void validate_nonsmooth_options(const NonsmoothContactOptions& o) {
  require_positive("nonsmooth/step_s", o.step_s);
  require_positive("nonsmooth/contact_margin_m", o.contact_margin_m);
  require_positive("nonsmooth/separation_time_s", o.separation_time_s);
  require_positive("nonsmooth/plane_margin_m", o.plane_margin_m);
  require_positive("nonsmooth/rest_speed_m_s", o.rest_speed_m_s);
  require_positive("nonsmooth/rest_time_s", o.rest_time_s);
  require_positive("nonsmooth/keep_margin_m", o.keep_margin_m);
  if (o.step_s > 0.01) {
    throw InvalidArgument("nonsmooth/step_s",
                          "nonsmooth/step_s must be at most 0.01 s, got " + format_value(o.step_s));
  }
  require_positive("nonsmooth/zeno_height_m", o.zeno_height_m);
  if (o.max_pair_impacts < 0) {
    throw InvalidArgument(
        "nonsmooth/max_pair_impacts",
        "nonsmooth/max_pair_impacts must be at least 0, got " + std::to_string(o.max_pair_impacts));
  }
  if (o.max_sweeps < 1) {
    throw InvalidArgument("nonsmooth/max_sweeps", "nonsmooth/max_sweeps must be at least 1, got " +
                                                      std::to_string(o.max_sweeps));
  }
}

NonsmoothIsland::NonsmoothIsland(std::vector<IslandBody> bodies,
                                 const ContactMaterial& board_material,
                                 const ContactMaterial& table_material,
                                 const ContactMaterial& stone_material, double t0_s,
                                 const NonsmoothContactOptions& options)
    : board_plastic_(plastic(board_material)),
      table_plastic_(plastic(table_material)),
      stone_plastic_(plastic(stone_material)),
      stone_material_(stone_material),
      options_(options),
      t0_(t0_s),
      reached_(t0_s) {
  require_finite("contact start time", t0_s);
  if (bodies.empty()) {
    throw InvalidArgument("island/bodies", "an island needs at least one body, got none");
  }
  validate_material("contact/board", board_material);
  validate_material("contact/table", table_material);
  validate_material("contact/stone", stone_material);
  validate_nonsmooth_options(options);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    require_finite("gravity", bodies[i].setup.gravity_world);
    if (bodies[i].setup.gravity_world != bodies.front().setup.gravity_world) {
      throw InvalidArgument("island/gravity", "island body " + std::to_string(i) +
                                                  " has a gravity other than body 0's: one "
                                                  "gravity for all members");
    }
  }
  for (IslandBody& b : bodies) {
    lattice_.states.push_back(b.state.validated());
    members_.push_back(Member{b.board, b.setup, b.board_enabled});
  }
  lattice_.active.assign(members_.size(), 1);
  lattice_.calm_steps.assign(members_.size(), 0);
  // Contacts between members that approach at formation are impacts at that instant (all gaps
  // within the margin close together: the vanishing gaps of Newton's cradle), before any flight.
  std::vector<MemberContacts> contacts(members_.size());
  std::vector<PairContact> pairs;
  gather(lattice_.states, contacts, pairs, true);
  resolve_pair_impacts(lattice_.states, contacts, pairs, free_of_board(contacts), true);
  lattice_.energy_j = energy(lattice_.states, lattice_.active);
  lattice_.ceiling_j = lattice_.energy_j;
}

double NonsmoothIsland::member_energy(std::size_t i, const RigidBodyState& s) const {
  return body_energy(members_[i].setup.model, s, members_[i].setup.gravity_world);
}

double NonsmoothIsland::energy(const std::vector<RigidBodyState>& s,
                               const std::vector<char>& active) const {
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (active[i]) e += member_energy(i, s[i]);
  }
  return e;
}

double NonsmoothIsland::potential(const std::vector<RigidBodyState>& s,
                                  const std::vector<char>& active) const {
  // body_energy with v = L = 0: the one formula, its kinetic terms exactly zero.
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!active[i]) continue;
    RigidBodyState still = s[i];
    still.velocity_world.setZero();
    still.angular_momentum_world.setZero();
    e += member_energy(i, still);
  }
  return e;
}

NonsmoothIsland::RigidMotion NonsmoothIsland::rigid_motion(
    const std::vector<RigidBodyState>& s) const {
  // The island as one rigid body: centre of mass X, velocity V, inertia about X
  // I = sum (I_i + m_i (|r_i|^2 1 - r_i r_i^T)), angular momentum about X L = sum (L_i + m_i r_i x
  // (v_i - V)), Omega = I^-1 L. Each member's share: v_i = V + Omega x r_i, L_i = I_i Omega.
  // The rest of the motion carries no momentum and no angular momentum, and its kinetic energy
  // adds to the rigid motion's (the cross terms are V . sum m dv + Omega . (sum m r x dv + I_i
  // dw) = 0).
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
  const Eigen::Vector3d v_centre = momentum / mass;
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
  const Eigen::Vector3d omega = inertia.ldlt().solve(spin);
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
  // The energy is a sum of terms (potential -m g . x about the world origin, kinetic), each
  // exact to an ulp or so: 16 epsilon of the sum of their magnitudes bounds its round-off.
  double magnitude = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!lattice_.active[i]) continue;
    RigidBodyState still = s[i];
    still.velocity_world.setZero();
    still.angular_momentum_world.setZero();
    const double p = member_energy(i, still);
    magnitude += std::abs(p) + std::abs(member_energy(i, s[i]) - p);
  }
  return 16.0 * std::numeric_limits<double>::epsilon() * magnitude;
}

bool NonsmoothIsland::scale_kinetic_energy(std::vector<RigidBodyState>& s, double energy_j,
                                           bool keep_momenta) const {
  // Velocity and angular momentum of all members scaled together: the kinetic energy is
  // quadratic in them, the potential energy and the poses do not change. Keeping the momenta
  // (an island free of the board: only internal forces act), the motion relative to the island's
  // rigid motion is scaled instead, and the rigid motion is kept.
  std::optional<RigidMotion> rigid;
  double fixed = potential(s, lattice_.active);
  if (keep_momenta) {
    rigid = rigid_motion(s);
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
  // The relative motion is only taken from, never grown: when it is almost gone (a row moving
  // as one) the factor that grows it to a round-off's worth of energy would be any number.
  if (keep && target > kinetic) return false;
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

bool NonsmoothIsland::free_of_board(const std::vector<MemberContacts>& mc) const {
  for (std::size_t i = 0; i < mc.size(); ++i) {
    // An obstacle is an outside body, as the board is.
    if (lattice_.active[i] && (mc[i].board > 0 || mc[i].obstacles > 0)) return false;
  }
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

void NonsmoothIsland::resolve_pair_impacts(std::vector<RigidBodyState>& s,
                                           std::vector<MemberContacts>& mc,
                                           const std::vector<PairContact>& pairs, bool free,
                                           bool commit) {
  // With e* = 0 the impacts are the plastic impulses of the sweeps (step 3's second part). Free
  // of the board, the World resolves every impact between flights itself (exact times, the
  // fastest approach first) and hands an island only touching contacts: none here.
  if (!options_.pair_impacts || free || pairs.empty() || !(stone_material_.restitution > 0.0)) {
    return;
  }
  const double zeno_mps =
      std::sqrt(2.0 * members_.front().setup.gravity_world.norm() * options_.zeno_height_m);
  const double impact_mps = std::max(kApproachToleranceMps, zeno_mps);
  for (int impacts = 0; impacts < options_.max_pair_impacts; ++impacts) {
    const PairContact* fastest = nullptr;
    double fastest_u_n = -impact_mps;
    for (const PairContact& p : pairs) {
      if (p.obstacle) continue;  // the plastic sweeps meet it (and wake it)
      const double u_n = p.normal_world.dot(
          point_velocity_world(members_[p.b].setup.model, s[p.b], p.point_world) -
          point_velocity_world(members_[p.a].setup.model, s[p.a], p.point_world));
      if (u_n < fastest_u_n) {  // ties: the first in the pair order
        fastest_u_n = u_n;
        fastest = &p;
      }
    }
    if (!fastest) return;
    const PairContact& p = *fastest;
    const MotionModel &ma = members_[p.a].setup.model, &mb = members_[p.b].setup.model;
    PairImpact impact =
        resolve_pair_impact(ma, s[p.a], mb, s[p.b], p.point_world, p.normal_world, stone_material_);
    if (impact.normal_velocity_after_mps < zeno_mps) {
      impact = resolve_pair_impact(ma, s[p.a], mb, s[p.b], p.point_world, p.normal_world,
                                   stone_plastic_);
    }
    s[p.a] = impact.state_a;
    s[p.b] = impact.state_b;
    mc[p.a].loaded = mc[p.b].loaded = true;
    if (commit) {
      ++counters_.impulses;
      ++counters_.pair_impulses;
      ++counters_.pair_impacts;
    }
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

void NonsmoothIsland::project(std::vector<RigidBodyState>& s, std::vector<MemberContacts>& mc,
                              bool commit, int& sweeps) {
  const std::size_t n = s.size();
  // The board normals each member lies on (within the margin after its board corrections).
  std::vector<int> supports(n, 0);
  std::vector<Eigen::Vector3d> support_normal(2 * n);
  for (sweeps = 0; sweeps < kMaxProjectionSweeps; ++sweeps) {
    bool corrected = false;
    // The board and the table: translate along the deeper contact's normal (their normals are
    // the separating directions, so one correction along one of them makes that gap zero).
    for (std::size_t i = 0; i < n; ++i) {
      if (!lattice_.active[i] || !members_[i].board_enabled) continue;
      for (int k = 0; k < kMaxCorrections; ++k) {
        const LensPose pose = lens_pose(s[i]);
        const BoardContact box = members_[i].board.box(pose), table = members_[i].board.table(pose);
        const BoardContact& deeper = table.lens.gap_m < box.lens.gap_m ? table : box;
        if (k == 0) {
          supports[i] = 0;
          for (const BoardContact* c : {&box, &table}) {
            if (c->lens.gap_m <= options_.contact_margin_m) {
              support_normal[2 * i + supports[i]++] = c->lens.normal_world;
            }
          }
        }
        if (deeper.lens.gap_m >= 0.0) break;
        if (commit) {
          counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -deeper.lens.gap_m);
          ++counters_.projections;
        }
        s[i].position_world += (kCorrectionSlackM - deeper.lens.gap_m) * deeper.lens.normal_world;
        mc[i].loaded = true;
        corrected = true;
      }
    }
    // Stone pairs: both along the pair normal, split by inverse mass; a stone that the
    // correction would press into a board contact it lies on stays (the board holds it).
    for (std::size_t a = 0; a < n; ++a) {
      if (!lattice_.active[a]) continue;
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!lattice_.active[b] ||
            apart_by_bounds(members_[a].board, s[a], members_[b].board, s[b], 0.0)) {
          continue;
        }
        const LensPose pa = lens_pose(s[a]), pb = lens_pose(s[b]);
        if (apart_along_last_normal(a, pa, b, pb, 0.0)) continue;
        const LensPairContact c = pair_contact(
            members_[a].board.lens(), pa, members_[b].board.lens(), pb,
            [&]() -> const LensPairContact& { return pair_distance(a, pa, b, pb, commit); });
        if (c.gap_m >= 0.0) continue;
        auto blocked = [&](std::size_t i, const Eigen::Vector3d& push) {
          for (int k = 0; k < supports[i]; ++k) {
            if (push.dot(support_normal[2 * i + k]) < -kBlockedCosine) return true;
          }
          return false;
        };
        double wa = 1.0 / members_[a].setup.model.mass_properties().mass();
        double wb = 1.0 / members_[b].setup.model.mass_properties().mass();
        const bool hold_a = blocked(a, -c.normal_world), hold_b = blocked(b, c.normal_world);
        if (hold_a != hold_b) {
          if (hold_a) wa = 0.0;
          if (hold_b) wb = 0.0;
        }
        const double depth = kCorrectionSlackM - c.gap_m;
        s[a].position_world -= (wa / (wa + wb) * depth) * c.normal_world;
        s[b].position_world += (wb / (wa + wb) * depth) * c.normal_world;
        if (commit) {
          counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -c.gap_m);
          ++counters_.projections;
          ++counters_.pair_projections;
        }
        mc[a].loaded = mc[b].loaded = true;
        corrected = true;
      }
    }
    if (project_obstacles(s, mc, commit)) corrected = true;
    if (!corrected) {
      ++sweeps;
      return;
    }
  }
}

bool NonsmoothIsland::project_obstacles(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc, bool commit) {
  // Only the member moves, along the pair normal by the whole overlap, as out of the board.
  bool corrected = false;
  for (std::size_t a = 0; a < s.size(); ++a) {
    if (!lattice_.active[a]) continue;
    for (std::size_t o = 0; o < obstacles_.size(); ++o) {
      const std::optional<LensPairContact> found = obstacle_contact(a, s[a], o, 0.0, commit);
      if (!found) continue;
      const LensPairContact& c = *found;
      if (c.gap_m >= 0.0) continue;
      if (c.gap_m < -kGapToleranceM) obstacle_acted_[o] = 1;
      s[a].position_world -= (kCorrectionSlackM - c.gap_m) * c.normal_world;
      if (commit) {
        counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -c.gap_m);
        ++counters_.projections;
        ++counters_.obstacle_projections;
      }
      mc[a].loaded = true;
      corrected = true;
    }
  }
  return corrected;
}

bool NonsmoothIsland::obstacle_impulses(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc,
                                        const std::vector<PairContact>& pairs, bool commit) {
  // The member's plastic impact on a fixed surface (the obstacle's, normal towards the member).
  bool acted = false;
  for (const PairContact& p : pairs) {
    if (!p.obstacle) continue;
    const MotionModel& model = members_[p.a].setup.model;
    const double u_n = -p.normal_world.dot(point_velocity_world(model, s[p.a], p.point_world));
    if (!(u_n < -kApproachToleranceMps)) continue;
    s[p.a] = resolve_impact(model, s[p.a], p.point_world, -p.normal_world, stone_plastic_,
                            members_[p.a].setup.gravity_world)
                 .state;
    obstacle_acted_[p.b] = 1;
    mc[p.a].loaded = true;
    acted = true;
    if (commit) {
      ++counters_.impulses;
      ++counters_.obstacle_impulses;
    }
  }
  return acted;
}

void NonsmoothIsland::set_obstacles(std::vector<IslandObstacle> obstacles) {
  for (IslandObstacle& o : obstacles) o.state = o.state.validated();
  obstacles_ = std::move(obstacles);
  obstacle_memo_.assign(members_.size() * obstacles_.size(), PairMemo{});
}

std::optional<LensPairContact> NonsmoothIsland::obstacle_contact(std::size_t a,
                                                                 const RigidBodyState& s_a,
                                                                 std::size_t o, double margin_m,
                                                                 bool commit) {
  const double reach =
      members_[a].board.lens().half_width() + obstacles_[o].lens.half_width() + margin_m;
  if ((obstacles_[o].state.position_world - s_a.position_world).squaredNorm() > reach * reach)
    return std::nullopt;
  const LensPose pa = lens_pose(s_a);
  return pair_contact(
      members_[a].board.lens(), pa, obstacles_[o].lens, lens_pose(obstacles_[o].state),
      [&]() -> const LensPairContact& { return obstacle_distance(a, pa, o, commit); });
}

const LensPairContact& NonsmoothIsland::obstacle_distance(std::size_t a, const LensPose& pa,
                                                          std::size_t o, bool commit) {
  // The obstacle does not move: the memo holds while the member's pose is the same (bitwise).
  PairMemo& m = obstacle_memo_[a * obstacles_.size() + o];
  const auto same = [](const LensPose& x, const LensPose& y) {
    return x.center_world == y.center_world && x.axis_world == y.axis_world;
  };
  if (m.valid && same(m.pose_a, pa)) {
    if (commit) ++counters_.pair_distance_reuses;
    return m.contact;
  }
  m.contact = lens_pair_distance(members_[a].board.lens(), pa, obstacles_[o].lens,
                                 lens_pose(obstacles_[o].state));
  m.pose_a = pa;
  m.valid = true;
  if (commit) ++counters_.pair_distances;
  return m.contact;
}

const LensPairContact& NonsmoothIsland::pair_distance(std::size_t a, const LensPose& pa,
                                                      std::size_t b, const LensPose& pb,
                                                      bool commit) {
  // One memo per ordered pair: the projection's last sweep (no correction) and gather see the
  // same poses, and so often do the next sub-step's checks. Its contact is a function of the
  // poses and of the pair's previous normal (the warm start), so the committed sub-steps alone
  // write it: a partial sub-step (a sample between lattice points) reads it and keeps its own
  // contact aside, and the lattice's motion does not depend on the sample times.
  const std::size_t n = members_.size();
  if (pair_memo_.size() != n * n) pair_memo_.assign(n * n, PairMemo{});
  PairMemo& m = pair_memo_[a * n + b];
  const auto same = [](const LensPose& x, const LensPose& y) {
    return x.center_world == y.center_world && x.axis_world == y.axis_world;
  };
  if (m.valid && same(m.pose_a, pa) && same(m.pose_b, pb)) {
    if (commit) ++counters_.pair_distance_reuses;
    return m.contact;
  }
  // Seen before: warm-started from its last normal (lens_pair_distance.h).
  const LensPairContact contact =
      m.valid ? lens_pair_distance_from(members_[a].board.lens(), pa, members_[b].board.lens(), pb,
                                        m.contact.normal_world)
              : lens_pair_distance(members_[a].board.lens(), pa, members_[b].board.lens(), pb);
  if (!commit) {
    partial_contact_ = contact;
    return partial_contact_;
  }
  m.contact = contact;
  m.pose_a = pa;
  m.pose_b = pb;
  m.valid = true;
  if (commit) ++counters_.pair_distances;
  return m.contact;
}

bool NonsmoothIsland::apart_along_last_normal(std::size_t a, const LensPose& pa, std::size_t b,
                                              const LensPose& pb, double gap_m) const {
  // The supporting-plane gap along the pair's last normal bounds its distance from below; where
  // it is positive the distance's ascent from that normal reaches the distance, and the push
  // contact's gap is at most a tolerance below it (lens_pair_distance.h). So above gap_m and
  // twice the tolerance, the pair's push contact is farther than gap_m: a check of one gap
  // instead of the distance (the projection's sweeps re-check pairs that one correction moved).
  const std::size_t n = members_.size();
  if (pair_memo_.size() != n * n) return false;
  const PairMemo& m = pair_memo_[a * n + b];
  return m.valid && lens_pair_gap_along(members_[a].board.lens(), pa, members_[b].board.lens(), pb,
                                        m.contact.normal_world) > gap_m + 2.0 * kGapToleranceM;
}

bool NonsmoothIsland::gather(const std::vector<RigidBodyState>& s, std::vector<MemberContacts>& mc,
                             std::vector<PairContact>& pairs, bool commit) {
  const std::size_t n = s.size();
  bool clear = true;
  pairs.clear();
  for (std::size_t i = 0; i < n; ++i) {
    mc[i].board = mc[i].stones = mc[i].near = 0;
    if (!lattice_.active[i] || !members_[i].board_enabled) continue;
    const LensPose pose = lens_pose(s[i]);
    for (const BoardContact& c : {members_[i].board.box(pose), members_[i].board.table(pose)}) {
      if (c.lens.gap_m < -kGapToleranceM) clear = false;
      if (c.lens.gap_m <= options_.contact_margin_m) mc[i].contact[mc[i].board++] = c;
    }
  }
  for (std::size_t a = 0; a < n; ++a) {
    if (!lattice_.active[a]) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      const double keep_m =
          std::max(options_.keep_margin_m, kKeepMarginFactor * options_.contact_margin_m);
      if (!lattice_.active[b] ||
          apart_by_bounds(members_[a].board, s[a], members_[b].board, s[b], keep_m)) {
        continue;
      }
      const LensPose pa = lens_pose(s[a]), pb = lens_pose(s[b]);
      if (apart_along_last_normal(a, pa, b, pb, keep_m)) continue;
      const LensPairContact c = pair_contact(
          members_[a].board.lens(), pa, members_[b].board.lens(), pb,
          [&]() -> const LensPairContact& { return pair_distance(a, pa, b, pb, commit); });
      if (c.gap_m < -kGapToleranceM) clear = false;
      if (c.gap_m > keep_m) continue;
      ++mc[a].near;
      ++mc[b].near;
      if (c.gap_m > options_.contact_margin_m) continue;
      ++mc[a].stones;
      ++mc[b].stones;
      pairs.push_back(PairContact{a, b, 0.5 * (c.point_a_world + c.point_b_world), c.normal_world});
    }
  }
  for (std::size_t a = 0; a < n; ++a) {
    mc[a].obstacles = 0;
    if (!lattice_.active[a]) continue;
    for (std::size_t o = 0; o < obstacles_.size(); ++o) {
      const std::optional<LensPairContact> found =
          obstacle_contact(a, s[a], o, options_.contact_margin_m, commit);
      if (!found) continue;
      const LensPairContact& c = *found;
      if (c.gap_m < -kGapToleranceM) clear = false;
      if (c.gap_m > options_.contact_margin_m) continue;
      ++mc[a].obstacles;
      pairs.push_back(
          PairContact{a, o, 0.5 * (c.point_a_world + c.point_b_world), c.normal_world, true});
    }
  }
  return clear;
}

bool NonsmoothIsland::board_impulses(std::size_t i, std::vector<RigidBodyState>& s,
                                     std::vector<MemberContacts>& mc,
                                     std::vector<Eigen::Vector3d>& accumulated,
                                     SweepCompliances& compliances, bool commit) {
  const MemberContacts& m = mc[i];
  const MotionModel& model = members_[i].setup.model;
  bool acted = false;
  for (int k = 0; k < m.board; ++k) {
    const BoardContact& c = m.contact[k];
    const ContactMaterial& material = c.on_table() ? table_plastic_ : board_plastic_;
    const Eigen::Vector3d& n = c.lens.normal_world;
    const Eigen::Vector3d& point = c.lens.point_world;
    Eigen::Vector3d& sum = accumulated[2 * i + static_cast<std::size_t>(k)];
    const Eigen::Vector3d u = point_velocity_world(model, s[i], point);
    if (n.dot(u) < -kApproachToleranceMps) {
      const Impact impact =
          resolve_impact(model, s[i], point, n, material, members_[i].setup.gravity_world);
      s[i] = impact.state;
      sum += impact.impulse_world;
    } else {
      if (!may_slip(n, u, sum, material.friction, kApproachToleranceMps)) continue;
      const Eigen::Vector3d p = friction_impulse(n, compliances.board(i, k, model, s[i], point), u,
                                                 sum, material.friction, kApproachToleranceMps);
      if (p.isZero()) continue;
      apply_impulse(model, s[i], point, p);
      sum += p;
    }
    acted = true;
    mc[i].loaded = true;
    if (commit) ++counters_.impulses;
  }
  return acted;
}

NonsmoothIsland::Step NonsmoothIsland::sub_step(const Lattice& lattice_from, double h_s,
                                                bool commit) {
  const std::vector<RigidBodyState>& from = lattice_from.states;
  const double energy_cap_j = lattice_from.energy_j;
  const std::size_t n = from.size();
  Step out;
  out.states = from;
  out.contacts.assign(n, MemberContacts{});
  obstacle_acted_.assign(obstacles_.size(), 0);
  // 1. Exact free flight.
  for (std::size_t i = 0; i < n; ++i) {
    if (lattice_.active[i]) out.states[i] = ExactMotion(members_[i].setup, from[i]).state_at(h_s);
  }
  std::vector<RigidBodyState>& s = out.states;

  // 2. Out of every overlap.
  int projection_sweeps = 0;
  project(s, out.contacts, commit, projection_sweeps);
  std::vector<PairContact> pairs;
  bool hold = false;
  if (!gather(s, out.contacts, pairs, commit)) {
    // The sweeps did not remove every overlap: keep the previous poses (below).
    hold = true;
    if (commit) ++counters_.projection_failures;
  }
  // Free of the board and the table, only the members' forces on each other act: momentum and
  // angular momentum follow their closed forms (the flight keeps them; the corrections keep the
  // momentum but not sum m x cross v, which the rigid rotation returns).
  const bool free = free_of_board(out.contacts);
  if (!hold && free) {
    out.anchor = lattice_from.anchor ? *lattice_from.anchor : anchor_of(from, lattice(steps_));
    keep_free_totals(s, *out.anchor, lattice(steps_) + h_s);
  }

  // 3. Impacts between members, the fastest approach first, at the material's e* (above the
  // impact speed; see the header), then plastic impulses at the contacts within the margin,
  // Gauss-Seidel until none approaches: the board's first (they carry the weight), then the pairs.
  if (!hold) resolve_pair_impacts(s, out.contacts, pairs, free, commit);
  int velocity_sweeps = 0;
  // Each contact's impulses so far in this sub-step (board: 2 per member; pairs: on b): their
  // normal part bounds the friction a contact that no longer approaches may still give.
  std::vector<Eigen::Vector3d> board_sum(2 * n, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> pair_sum(pairs.size(), Eigen::Vector3d::Zero());
  SweepCompliances compliances(n, pairs.size());  // the poses stay through the sweeps
  for (; !hold && velocity_sweeps < options_.max_sweeps; ++velocity_sweeps) {
    bool acted = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (board_impulses(i, s, out.contacts, board_sum, compliances, commit)) acted = true;
    }
    if (obstacle_impulses(s, out.contacts, pairs, commit)) acted = true;
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      const PairContact& p = pairs[j];
      if (p.obstacle) continue;
      const MotionModel &ma = members_[p.a].setup.model, &mb = members_[p.b].setup.model;
      const Eigen::Vector3d u = point_velocity_world(mb, s[p.b], p.point_world) -
                                point_velocity_world(ma, s[p.a], p.point_world);
      const double u_n = p.normal_world.dot(u);
      if (!(u_n < -kApproachToleranceMps)) {
        // Not approaching: the friction its normal impulse so far allows, if it slips.
        if (!may_slip(p.normal_world, u, pair_sum[j], stone_plastic_.friction,
                      kApproachToleranceMps)) {
          continue;
        }
        const Eigen::Vector3d f = friction_impulse(
            p.normal_world, compliances.pair(j, p.a, ma, s[p.a], p.b, mb, s[p.b], p.point_world), u,
            pair_sum[j], stone_plastic_.friction, kApproachToleranceMps);
        if (f.isZero()) continue;
        apply_impulse(mb, s[p.b], p.point_world, f);
        apply_impulse(ma, s[p.a], p.point_world, -f);
        pair_sum[j] += f;
        acted = true;
        out.contacts[p.a].loaded = out.contacts[p.b].loaded = true;
        if (commit) {
          ++counters_.impulses;
          ++counters_.pair_impulses;
        }
        continue;
      }
      auto pressed = [&](std::size_t i, const Eigen::Vector3d& push) {
        const MemberContacts& m = out.contacts[i];
        for (int k = 0; k < m.board; ++k) {
          if (push.dot(m.contact[k].lens.normal_world) < -kPressedCosine) return true;
        }
        return false;
      };
      const bool shock = velocity_sweeps >= kPlainSweeps;
      const bool held_a = shock && pressed(p.a, -p.normal_world);
      const bool held_b = shock && pressed(p.b, p.normal_world);
      if (held_a != held_b) {
        // The board holds the lower stone: the upper one meets it as a surface moving with the
        // lower's contact point (the one-body impact in that frame: only K of the upper stone
        // and the relative velocity enter). The lower stone takes the opposite impulse -P at the
        // same point (momentum between the stones is kept), and at once its board contacts'
        // plastic impulses (the board's part: the normal, and the tangential within mu N), so
        // the board takes only what its contacts can carry and the rest stays in the stones:
        // on a frictionless board the horizontal momentum is kept to round-off. Along the
        // board's normal the lower stone is then where it was (a stone on a stone converges at
        // once); what the board cannot carry the next sweep meets. The guard covers the energy.
        const std::size_t held = held_a ? p.a : p.b, moving = held_a ? p.b : p.a;
        const Eigen::Vector3d n = held_a ? p.normal_world : Eigen::Vector3d(-p.normal_world);
        RigidBodyState relative = s[moving];
        relative.velocity_world -=
            point_velocity_world(members_[held].setup.model, s[held], p.point_world);
        const Impact impact =
            resolve_impact(members_[moving].setup.model, relative, p.point_world, n, stone_plastic_,
                           members_[moving].setup.gravity_world);
        s[moving].velocity_world += impact.state.velocity_world - relative.velocity_world;
        s[moving].angular_momentum_world = impact.state.angular_momentum_world;
        apply_impulse(members_[held].setup.model, s[held], p.point_world, -impact.impulse_world);
        pair_sum[j] += held_a ? impact.impulse_world : Eigen::Vector3d(-impact.impulse_world);
        board_impulses(held, s, out.contacts, board_sum, compliances, commit);
      } else {
        const PairImpact impact = resolve_pair_impact(ma, s[p.a], mb, s[p.b], p.point_world,
                                                      p.normal_world, stone_plastic_);
        s[p.a] = impact.state_a;
        s[p.b] = impact.state_b;
        pair_sum[j] += impact.impulse_world;
      }
      acted = true;
      out.contacts[p.a].loaded = out.contacts[p.b].loaded = true;
      if (commit) {
        ++counters_.impulses;
        ++counters_.pair_impulses;
      }
    }
    if (!acted) {
      ++velocity_sweeps;
      break;
    }
  }

  // 4. The energy guard over the island: never above the previous lattice state's energy. Free
  // of the board with two members or more, an excess within the energy's own round-off is left
  // (the exact flight, which no impulse changed, hands out such states too): scaling it away
  // would change the momenta. (One member has no motion beyond the rigid one: scaled as before.)
  // That allowance never takes it above the energy at the island's formation (ceiling_j), so
  // round-off cannot walk it upward over the sub-steps.
  const double energy_now_j = energy(s, lattice_.active);
  const bool round_off_only =
      free && std::count(lattice_.active.begin(), lattice_.active.end(), 1) > 1 &&
      energy_now_j - energy_cap_j <= energy_round_off(s) && energy_now_j <= lattice_from.ceiling_j;
  if (!hold && !round_off_only && energy(s, lattice_.active) > energy_cap_j) {
    if (commit) ++counters_.energy_guard_scalings;
    // Free: the motion relative to the rigid motion first (momenta kept), else all of it.
    const bool scaled = (free && scale_kinetic_energy(s, energy_cap_j, true)) ||
                        scale_kinetic_energy(s, energy_cap_j, false);
    if (!scaled || energy(s, lattice_.active) > energy_cap_j) {
      hold = true;  // the lift cannot be paid for
    }
  }
  if (hold) {
    // The members touching something keep their previous poses, still; free members keep their
    // exact flight (energy conserved to round-off). If even that is above the cap, all keep
    // their previous poses: then the energy is the previous potential energy, <= the cap.
    if (commit) ++counters_.holds;
    for (std::size_t i = 0; i < n; ++i) {
      if (!lattice_.active[i]) continue;
      const bool free = out.contacts[i].board == 0 && out.contacts[i].stones == 0 &&
                        out.contacts[i].obstacles == 0 && !out.contacts[i].loaded;
      if (free) continue;
      s[i] = from[i];
      s[i].velocity_world.setZero();
      s[i].angular_momentum_world.setZero();
      out.contacts[i].loaded = true;
    }
    if (energy(s, lattice_.active) > energy_cap_j) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!lattice_.active[i]) continue;
        s[i] = from[i];
        s[i].velocity_world.setZero();
        s[i].angular_momentum_world.setZero();
      }
    }
    gather(s, out.contacts, pairs, commit);
  }
  if (commit) {
    counters_.projection_sweeps += projection_sweeps;
    counters_.velocity_sweeps += velocity_sweeps;
    counters_.most_projection_sweeps =
        std::max(counters_.most_projection_sweeps, projection_sweeps);
    counters_.most_velocity_sweeps = std::max(counters_.most_velocity_sweeps, velocity_sweeps);
    const double excess = energy(s, lattice_.active) - energy_cap_j;
    if (excess > 0.0) {
      counters_.largest_energy_excess_j = std::max(counters_.largest_energy_excess_j, excess);
    }
    for (std::size_t o = 0; o < obstacle_acted_.size(); ++o) {
      if (obstacle_acted_[o]) out.woken.push_back(o);
    }
  }
  return out;
}

NonsmoothIsland::Lattice NonsmoothIsland::next_lattice() {
  const double t = lattice(steps_ + 1);
  const double h = t - lattice(steps_);
  const Step step = sub_step(lattice_, h, true);
  Lattice next = lattice_;
  next.states = step.states;
  next.anchor = step.anchor;
  next.left.clear();
  next.woken = step.woken;
  if (!next.woken.empty()) return next;  // not to be committed (advance)
  const std::size_t n = next.states.size();
  const NonsmoothContactOptions& o = options_;
  auto calm_for_long = [&](std::size_t i) {
    return static_cast<double>(next.calm_steps[i]) * o.step_s >= o.rest_time_s;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!next.active[i]) continue;
    const RigidBodyState& s = next.states[i];
    const Eigen::Vector3d omega =
        members_[i].setup.model.angular_velocity_world(s.orientation, s.angular_momentum_world);
    const double rim_speed = omega.norm() * members_[i].board.lens().half_width();
    const bool calm = s.velocity_world.norm() <= o.rest_speed_m_s && rim_speed <= o.rest_speed_m_s;
    next.calm_steps[i] = calm ? next.calm_steps[i] + 1 : 0;
  }
  std::vector<char> leaving(n, 0);
  auto leave = [&](std::size_t i, NonsmoothEnd end) {
    IslandMemberEnd e;
    e.member = i;
    e.end = end;
    if (end == NonsmoothEnd::rest) {
      next.states[i].velocity_world.setZero();
      next.states[i].angular_momentum_world.setZero();
    }
    next.left.push_back(e);
    leaving[i] = 1;
    return &next.left.back();
  };
  // The plane model first: a member alone on the top face or the table.
  for (std::size_t i = 0; i < n; ++i) {
    const MemberContacts& m = step.contacts[i];
    if (!next.active[i] || m.near > 0 || !m.loaded || m.board != 1) continue;
    const BoardContact& c = m.contact[0];
    const RigidBodyState& s = next.states[i];
    const double u_n = c.lens.normal_world.dot(
        point_velocity_world(members_[i].setup.model, s, c.lens.point_world));
    const std::optional<SupportPlane> plane =
        support_plane(members_[i].board, c, lens_pose(s), o.plane_margin_m);
    if (plane && std::abs(u_n) <= kPlaneNormalSpeedMps) {
      IslandMemberEnd* e = leave(i, NonsmoothEnd::plane);
      e->plane = plane;
      e->contact = c;
    }
  }
  // Rest of the island as a whole: everyone else touching something and calm for long enough.
  bool all_rest = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (!next.active[i] || leaving[i]) continue;
    const MemberContacts& m = step.contacts[i];
    if (m.board + m.stones + m.obstacles == 0 || !calm_for_long(i)) all_rest = false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!next.active[i] || leaving[i]) continue;
    const MemberContacts& m = step.contacts[i];
    if (all_rest) {
      leave(i, NonsmoothEnd::rest);
      continue;
    }
    if (m.near > 0) continue;
    if (m.board > 0 && calm_for_long(i)) {
      leave(i, NonsmoothEnd::rest);
      continue;
    }
    if (m.loaded) continue;
    // Separated: free of the board (exact time of impact) and out of every other member's
    // reach for separation_time_s (a bound: relative speed, rims' speeds, gravity).
    const RigidBodyState& s = next.states[i];
    bool reachable = false;
    for (std::size_t j = 0; j < n && !reachable; ++j) {
      if (j == i || !next.active[j]) continue;
      const RigidBodyState& r = next.states[j];
      auto rim = [&](std::size_t k, const RigidBodyState& x) {
        return members_[k]
                   .setup.model.angular_velocity_world(x.orientation, x.angular_momentum_world)
                   .norm() *
               members_[k].board.lens().half_width();
      };
      const double ts = o.separation_time_s;
      const double reach = (s.velocity_world - r.velocity_world).norm() * ts +
                           (rim(i, s) + rim(j, r)) * ts +
                           members_[i].setup.gravity_world.norm() * ts * ts + o.contact_margin_m;
      const LensPose pi = lens_pose(s), pj = lens_pose(r);
      if (!apart_by_bounds(members_[i].board, s, members_[j].board, r, reach) &&
          !apart_along_last_normal(i, pi, j, pj, reach)) {
        reachable = pair_distance(i, pi, j, pj, true).gap_m <= reach;
      }
    }
    if (reachable) continue;
    if (!members_[i].board_enabled) {
      leave(i, NonsmoothEnd::separated);
      continue;
    }
    ++counters_.separation_searches;
    const TimeOfImpact toi = board_time_of_impact(members_[i].board, members_[i].setup, s, t, t,
                                                  t + o.separation_time_s);
    if (!toi.hit && !toi.exhausted) leave(i, NonsmoothEnd::separated);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (leaving[i]) next.active[i] = 0;
  }
  next.energy_j = energy(next.states, next.active);
  if (!next.left.empty()) {
    // The members still in form the island anew: their totals and energy from here.
    next.anchor.reset();
    next.ceiling_j = next.energy_j;
  } else {
    // The lowest energy so far plus one evaluation's round-off, never above the formation's:
    // the allowance cannot walk upward (the impulses' losses are not won back by round-off).
    next.ceiling_j = std::min(lattice_.ceiling_j, next.energy_j + energy_round_off(next.states));
  }
  return next;
}

IslandOutcome NonsmoothIsland::outcome(double t) const {
  IslandOutcome o;
  o.time_s = t;
  o.states = lattice_.states;
  return o;
}

IslandOutcome NonsmoothIsland::wake_outcome(const std::vector<std::size_t>& woken) {
  // A sub-step is computed fresh only from a lattice point no call has gone past (a sample
  // computes it first), so the World's stones are not beyond lattice(steps_).
  reached_ = lattice(steps_);
  IslandOutcome o = outcome(reached_);
  o.woken = woken;
  counters_.obstacle_wakes += static_cast<long>(woken.size());
  return o;
}

IslandOutcome NonsmoothIsland::advance(double t_end_s, long max_steps) {
  require_finite("nonsmooth advance time", t_end_s);
  if (max_steps < 0) {
    throw InvalidArgument(
        "max_steps", "nonsmooth advance: max_steps must be >= 0, got " + std::to_string(max_steps));
  }
  if (finished_) {
    if (t_end_s != finished_->time_s) {
      throw InvalidArgument("t_end_s",
                            "nonsmooth contact ended at t = " + format_value(finished_->time_s) +
                                " s; it cannot be advanced to " + format_value(t_end_s) + " s");
    }
    return *finished_;
  }
  if (t_end_s < reached_) {
    throw InvalidArgument("t_end_s", "nonsmooth advance time " + format_value(t_end_s) +
                                         " s is before the time already reached, " +
                                         format_value(reached_) + " s");
  }
  for (long taken = 0; lattice(steps_ + 1) <= t_end_s; ++taken) {
    const double t = lattice(steps_ + 1);
    if (taken >= max_steps) {
      // The budget is spent: stop at the last lattice point (or where the previous call
      // stopped, if later), to be continued.
      t_end_s = std::max(reached_, lattice(steps_));
      break;
    }
    Lattice next = ahead_ ? std::move(*ahead_) : next_lattice();
    ahead_.reset();
    if (!next.woken.empty()) return wake_outcome(next.woken);
    ++steps_;
    ++counters_.steps;
    lattice_ = std::move(next);
    if (!lattice_.left.empty()) {
      reached_ = t;
      IslandOutcome o = outcome(t);
      o.left = lattice_.left;
      o.finished = std::none_of(lattice_.active.begin(), lattice_.active.end(),
                                [](char a) { return a != 0; });
      if (o.finished) finished_ = o;
      return o;
    }
  }
  const double since = t_end_s - lattice(steps_);
  if (since <= 0.0) {
    reached_ = t_end_s;
    return outcome(t_end_s);
  }
  // The next lattice state first: a sub-step to it that wakes obstacles is redone by the World
  // from lattice(steps_), which no sample has passed yet.
  if (!ahead_) ahead_ = next_lattice();
  if (!ahead_->woken.empty()) return wake_outcome(ahead_->woken);
  reached_ = t_end_s;
  // A sample between lattice points: the partial sub-step's poses with the island's energy set
  // to that of the next lattice state (computed ahead; committing it later gives the same
  // state), so the energies handed out never rise; when scaling cannot reach it (no kinetic
  // energy, or the potential above it), the next lattice state itself.
  ++counters_.samples;
  const double next_j = energy(ahead_->states, lattice_.active);
  Step partial = sub_step(lattice_, since, false);
  IslandOutcome o;
  o.time_s = t_end_s;
  // Free of the board: as it is when its energy is next_j to round-off, else the motion
  // relative to the rigid motion scaled (momenta kept), else all of it.
  const bool free = free_of_board(partial.contacts);
  const double partial_j = energy(partial.states, lattice_.active);
  if (free && std::count(lattice_.active.begin(), lattice_.active.end(), 1) > 1 &&
      std::abs(partial_j - next_j) <= energy_round_off(partial.states) &&
      partial_j <= lattice_.energy_j + energy_round_off(partial.states) &&
      partial_j <= lattice_.ceiling_j) {
    o.states = partial.states;
    for (std::size_t i = 0; i < o.states.size(); ++i) {
      if (!lattice_.active[i]) o.states[i] = lattice_.states[i];
    }
    return o;
  }
  std::optional<RigidMotion> rigid;
  bool scaled = false;
  if (free) {
    rigid = rigid_motion(partial.states);
    scaled = scale_kinetic_energy(partial.states, next_j, true);
  }
  if (!scaled) {
    rigid.reset();
    scaled = scale_kinetic_energy(partial.states, next_j, false);
  }
  // Round-off can leave it ulps below next_j: grow it back as little as needed (by a millionth
  // at most: more is not round-off).
  for (double grow = 1e-15;
       scaled && grow < 1e-6 && energy(partial.states, lattice_.active) < next_j; grow *= 4.0) {
    scale_motion(partial.states, 1.0 + grow, rigid ? &*rigid : nullptr);
  }
  const double e = energy(partial.states, lattice_.active);
  if (scaled && e >= next_j && e <= lattice_.energy_j) {
    o.states = partial.states;
  } else {
    o.states = ahead_->states;
  }
  for (std::size_t i = 0; i < o.states.size(); ++i) {
    if (!lattice_.active[i]) o.states[i] = lattice_.states[i];
  }
  return o;
}

}  // namespace virtual_go
