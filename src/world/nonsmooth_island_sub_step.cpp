// NonsmoothIsland::sub_step, one sub-step of the Moreau-Jean scheme (nonsmooth_island.h, steps 1
// to 4), and its velocity stage: the impacts between members and the plastic impulses and
// friction at the board's, the obstacles' and the pairs' contacts (their maths: island_impulses).
#include <algorithm>
#include <cmath>

#include "nonsmooth_island_impl.h"
#include "virtual_go/contact/coulomb_plastic_impulse.h"
#include "virtual_go/contact/pair_impact.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/world/island_impulses.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace virtual_go {
namespace {

// Contact-point normal speeds above -this (m/s) are not approaching: they move a contact by less
// than 1e-16 m in a sub-step.
constexpr double kApproachToleranceMps = 1e-12;
// A pair impulse does not move a stone it would press into a board contact it lies on with a
// cosine above this (mostly into the board: a stone under another, not one pushed along a row).
constexpr double kPressedCosine = 0.5;

void apply_impulse(const MotionModel& model, RigidBodyState& s, const Eigen::Vector3d& point_world,
                   const Eigen::Vector3d& impulse_world) {
  s.velocity_world += impulse_world / model.mass_properties().mass();
  s.angular_momentum_world += (point_world - s.position_world).cross(impulse_world);
}

}  // namespace

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
  std::vector<PairContact>& pairs = sweep_.pairs;
  pairs.clear();
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
  std::vector<Eigen::Vector3d>& board_sum = sweep_.board_sum;
  std::vector<Eigen::Vector3d>& pair_sum = sweep_.pair_sum;
  board_sum.assign(2 * n, Eigen::Vector3d::Zero());
  pair_sum.assign(pairs.size(), Eigen::Vector3d::Zero());
  SweepCompliances& compliances = sweep_.compliances;  // the poses stay through the sweeps
  compliances.reset(n, pairs.size());
  SweepSettled& settled = sweep_.settled;
  settled.reset(n, pairs.size());
  const bool joint_velocities = options_.joint_solve && !free;
  // Free of the board the sweeps below are exact (a free island keeps its totals in closed form,
  // and a row in the air is the plastic cradle to round-off): the joint solve is for islands on
  // the board.
  if (!hold && joint_velocities) {
    velocity_sweeps = velocities_jointly(s, out.contacts, pairs, commit);
  }
  for (; !hold && !joint_velocities && velocity_sweeps < options_.max_sweeps; ++velocity_sweeps) {
    bool acted = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (board_impulses(i, s, out.contacts, board_sum, compliances, settled, commit)) {
        acted = true;
      }
    }
    if (obstacle_impulses(s, out.contacts, pairs, compliances, settled, commit)) acted = true;
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      const PairContact& p = pairs[j];
      if (p.obstacle || settled.pair(j, p.a, p.b)) continue;
      const MotionModel &ma = members_[p.a].setup.model, &mb = members_[p.b].setup.model;
      const Eigen::Vector3d u = compliances.point_velocity(p.b, mb, s[p.b], p.point_world) -
                                compliances.point_velocity(p.a, ma, s[p.a], p.point_world);
      const double u_n = p.normal_world.dot(u);
      if (!(u_n < -kApproachToleranceMps)) {
        // Not approaching: the friction its normal impulse so far allows, if it slips.
        if (!may_slip(p.normal_world, u, pair_sum[j], stone_plastic_.friction,
                      kApproachToleranceMps)) {
          settled.pair_idle(j, p.a, p.b);
          continue;
        }
        const Eigen::Vector3d f = friction_impulse(
            p.normal_world, compliances.pair(j, p.a, ma, s[p.a], p.b, mb, s[p.b], p.point_world), u,
            pair_sum[j], stone_plastic_.friction, kApproachToleranceMps);
        if (f.isZero()) {
          settled.pair_idle(j, p.a, p.b);
          continue;
        }
        apply_impulse(mb, s[p.b], p.point_world, f);
        apply_impulse(ma, s[p.a], p.point_world, -f);
        settled.changed(p.a);
        settled.changed(p.b);
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
      const bool shock = velocity_sweeps >= kNonsmoothPlainSweeps;
      const bool held_a = shock && pressed(p.a, -p.normal_world);
      const bool held_b = shock && pressed(p.b, p.normal_world);
      if (held_a != held_b) {
        // The board holds the lower stone: the upper one meets it as a surface moving with the
        // lower's contact point (the one-body plastic impulse in that frame: only K of the upper
        // stone and the relative velocity enter). The lower stone takes the opposite impulse -P at
        // the same point (momentum between the stones is kept), and at once its board contacts'
        // plastic impulses (the board's part: the normal, and the tangential within mu N), so
        // the board takes only what its contacts can carry and the rest stays in the stones:
        // on a frictionless board the horizontal momentum is kept to round-off. Along the
        // board's normal the lower stone is then where it was (a stone on a stone converges at
        // once); what the board cannot carry the next sweep meets. The guard covers the energy.
        const std::size_t held = held_a ? p.a : p.b, moving = held_a ? p.b : p.a;
        const Eigen::Vector3d n = held_a ? p.normal_world : Eigen::Vector3d(-p.normal_world);
        const MotionModel& moving_model = members_[moving].setup.model;
        const Eigen::Vector3d u_moving =
            compliances.point_velocity(moving, moving_model, s[moving], p.point_world) -
            compliances.point_velocity(held, members_[held].setup.model, s[held], p.point_world);
        const PlasticImpulse impulse = coulomb_plastic_impulse(
            n, compliances.member_at(moving, moving_model, s[moving], p.point_world), u_moving,
            stone_plastic_.friction);
        apply_impulse(moving_model, s[moving], p.point_world, impulse.impulse_world);
        apply_impulse(members_[held].setup.model, s[held], p.point_world, -impulse.impulse_world);
        settled.changed(moving);
        settled.changed(held);
        pair_sum[j] += held_a ? impulse.impulse_world : Eigen::Vector3d(-impulse.impulse_world);
        if (commit && impulse.frictionless) ++counters_.frictionless_impulses;
        board_impulses(held, s, out.contacts, board_sum, compliances, settled, commit);
      } else {
        const PlasticImpulse impulse = coulomb_plastic_impulse(
            p.normal_world, compliances.pair(j, p.a, ma, s[p.a], p.b, mb, s[p.b], p.point_world), u,
            stone_plastic_.friction);
        apply_impulse(mb, s[p.b], p.point_world, impulse.impulse_world);
        apply_impulse(ma, s[p.a], p.point_world, -impulse.impulse_world);
        settled.changed(p.a);
        settled.changed(p.b);
        pair_sum[j] += impulse.impulse_world;
        if (commit && impulse.frictionless) ++counters_.frictionless_impulses;
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
  double round_off_now_j = 0.0;
  const double energy_now_j = energy(s, lattice_.active, &round_off_now_j);
  const bool round_off_only =
      free && std::count(lattice_.active.begin(), lattice_.active.end(), 1) > 1 &&
      energy_now_j - energy_cap_j <= round_off_now_j && energy_now_j <= lattice_from.ceiling_j;
  // The energy handed out (and its round-off): energy_now_j unless the guard or a hold below
  // changes the states.
  double energy_out_j = energy_now_j, round_off_out_j = round_off_now_j;
  if (!hold && !round_off_only && energy_now_j > energy_cap_j) {
    if (commit) ++counters_.energy_guard_scalings;
    // The motion relative to the rigid motion that carries the kept totals first, else all of
    // it.
    const Kept kept = kept_totals(out.contacts);
    const bool scaled = (kept != Kept::none && scale_kinetic_energy(s, energy_cap_j, kept)) ||
                        scale_kinetic_energy(s, energy_cap_j, Kept::none);
    energy_out_j = energy(s, lattice_.active, &round_off_out_j);
    if (!scaled || energy_out_j > energy_cap_j) {
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
    energy_out_j = energy(s, lattice_.active, &round_off_out_j);
  }
  out.energy_j = energy_out_j;
  out.round_off_j = round_off_out_j;
  if (commit) {
    counters_.projection_sweeps += projection_sweeps;
    counters_.velocity_sweeps += velocity_sweeps;
    counters_.most_projection_sweeps =
        std::max(counters_.most_projection_sweeps, projection_sweeps);
    counters_.most_velocity_sweeps = std::max(counters_.most_velocity_sweeps, velocity_sweeps);
    const double excess = energy_out_j - energy_cap_j;
    if (excess > 0.0) {
      counters_.largest_energy_excess_j = std::max(counters_.largest_energy_excess_j, excess);
    }
    for (std::size_t o = 0; o < obstacle_acted_.size(); ++o) {
      if (obstacle_acted_[o]) out.woken.push_back(o);
    }
  }
  return out;
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

bool NonsmoothIsland::board_impulses(std::size_t i, std::vector<RigidBodyState>& s,
                                     std::vector<MemberContacts>& mc,
                                     std::vector<Eigen::Vector3d>& accumulated,
                                     SweepCompliances& compliances, SweepSettled& settled,
                                     bool commit) {
  const MemberContacts& m = mc[i];
  const MotionModel& model = members_[i].setup.model;
  bool acted = false;
  for (int k = 0; k < m.board; ++k) {
    const std::size_t slot = 2 * i + static_cast<std::size_t>(k);
    if (settled.board(slot, i)) continue;
    const BoardContact& c = m.contact[k];
    const ContactMaterial& material = c.on_table() ? table_plastic_ : board_plastic_;
    const Eigen::Vector3d& n = c.lens.normal_world;
    const Eigen::Vector3d& point = c.lens.point_world;
    Eigen::Vector3d& sum = accumulated[slot];
    const Eigen::Vector3d u = compliances.point_velocity(i, model, s[i], point);
    if (n.dot(u) < -kApproachToleranceMps) {
      const PlasticImpulse impulse = coulomb_plastic_impulse(
          n, compliances.board(i, k, model, s[i], point), u, material.friction);
      apply_impulse(model, s[i], point, impulse.impulse_world);
      sum += impulse.impulse_world;
      if (commit && impulse.frictionless) ++counters_.frictionless_impulses;
    } else {
      if (!may_slip(n, u, sum, material.friction, kApproachToleranceMps)) {
        settled.board_idle(slot, i);
        continue;
      }
      const Eigen::Vector3d p = friction_impulse(n, compliances.board(i, k, model, s[i], point), u,
                                                 sum, material.friction, kApproachToleranceMps);
      if (p.isZero()) {
        settled.board_idle(slot, i);
        continue;
      }
      apply_impulse(model, s[i], point, p);
      sum += p;
    }
    settled.changed(i);
    acted = true;
    mc[i].loaded = true;
    if (commit) ++counters_.impulses;
  }
  return acted;
}

bool NonsmoothIsland::obstacle_impulses(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc,
                                        const std::vector<PairContact>& pairs,
                                        SweepCompliances& compliances, SweepSettled& settled,
                                        bool commit) {
  // The member's plastic impulse on a fixed surface (the obstacle's, normal towards the member),
  // by the same local Coulomb law as every other plastic impulse of the sweeps.
  bool acted = false;
  for (std::size_t j = 0; j < pairs.size(); ++j) {
    const PairContact& p = pairs[j];
    if (!p.obstacle || settled.obstacle(j, p.a)) continue;
    const MotionModel& model = members_[p.a].setup.model;
    const Eigen::Vector3d n = -p.normal_world;
    const Eigen::Vector3d u = compliances.point_velocity(p.a, model, s[p.a], p.point_world);
    if (!(n.dot(u) < -kApproachToleranceMps)) {
      settled.obstacle_idle(j, p.a);
      continue;
    }
    const PlasticImpulse impulse = coulomb_plastic_impulse(
        n, compliances.member_at(p.a, model, s[p.a], p.point_world), u, stone_plastic_.friction);
    apply_impulse(model, s[p.a], p.point_world, impulse.impulse_world);
    settled.changed(p.a);
    if (commit && impulse.frictionless) ++counters_.frictionless_impulses;
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

}  // namespace virtual_go
