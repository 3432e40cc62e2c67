// NonsmoothIsland's options and construction, and the lattice driver: advance() commits the
// sub-steps (nonsmooth_island_sub_step.cpp) lattice point by lattice point, samples between
// them, and decides at each lattice point which members leave the island and how.
#include "virtual_go/world/nonsmooth_island.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "nonsmooth_island_impl.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/world/world_body.h"

namespace virtual_go {
namespace {

// The plane model accepts |u_n| <= 1e-6 m/s; hand over only well inside that.
constexpr double kPlaneNormalSpeedMps = 1e-7;
// A member no nearer than this (m) to any other member or obstacle leans on none of them: the
// contacts' gaps stay within nanometres (the contact margin, the corrections' slack).
constexpr double kLeanGapM = 1e-6;
// A contact normal within this (1 - cosine) of -gravity is a face across gravity; G over the
// contact point within l_r plus this (m) balances (round-off of the witness point).
constexpr double kAcrossGravityTolerance = 1e-12;
constexpr double kBalanceToleranceM = 1e-12;
// A sample's growth back to the next lattice energy: at most this factor above 1 (more is not
// round-off), and bisections of its bracket (of width 3/4 of its top: 50 leave it to round-off).
constexpr double kLargestRoundOffGrowth = 1e-6;
constexpr int kGrowthBisections = 50;

ContactMaterial plastic(ContactMaterial m) {
  m.restitution = 0.0;
  return m;
}

using nonsmooth_island_detail::apart_by_bounds;

}  // namespace

void validate_nonsmooth_options(const NonsmoothContactOptions& o) {
  require_positive("nonsmooth/step_s", o.step_s);
  require_positive("nonsmooth/contact_margin_m", o.contact_margin_m);
  require_positive("nonsmooth/separation_time_s", o.separation_time_s);
  require_positive("nonsmooth/plane_margin_m", o.plane_margin_m);
  require_positive("nonsmooth/rest_speed_mps", o.rest_speed_mps);
  require_positive("nonsmooth/rest_time_s", o.rest_time_s);
  require_positive("nonsmooth/keep_margin_m", o.keep_margin_m);
  for (const auto& [field, value] :
       {std::pair<const char*, double>{"nonsmooth/keep_s_per_mps", o.keep_s_per_mps},
        {"nonsmooth/keep_join_m", o.keep_join_m}}) {
    if (!(std::isfinite(value) && value >= 0.0)) {
      throw InvalidArgument(
          field, std::string(field) + " must be finite and at least 0, got " + format_value(value));
    }
  }
  if (o.step_s > kNonsmoothLargestStepS) {
    throw InvalidArgument("nonsmooth/step_s",
                          "nonsmooth/step_s must be at most " +
                              format_value(kNonsmoothLargestStepS) +
                              " s (coarser island sub-steps do not keep the island's momentum and "
                              "rest; nonsmooth_island.h), got " +
                              format_value(o.step_s));
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
    members_.push_back(Member{b.board, b.setup, b.board_enabled, b.lowest_potential_j});
  }
  lattice_.active.assign(members_.size(), 1);
  lattice_.calm_steps.assign(members_.size(), 0);
  // With the energy rule, the margin starts from the formation's energy and only narrows; a
  // member without a lowest potential gives no bound, and then the configured margin holds.
  lattice_.keep_margin_m = options_.keep_s_per_mps > 0.0 ? std::numeric_limits<double>::infinity()
                                                         : options_.keep_margin_m;
  narrow_keep_margin(lattice_);
  if (!std::isfinite(lattice_.keep_margin_m)) lattice_.keep_margin_m = options_.keep_margin_m;
  // Contacts between members that approach at formation are impacts at that instant (all gaps
  // within the margin close together: the vanishing gaps of Newton's cradle), before any flight.
  std::vector<MemberContacts> contacts(members_.size());
  std::vector<PairContact> pairs;
  gather(lattice_.states, contacts, pairs, true);
  resolve_pair_impacts(lattice_.states, contacts, pairs, free_of_board(contacts), true);
  lattice_.energy_j = energy(lattice_.states, lattice_.active);
  lattice_.ceiling_j = lattice_.energy_j;
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
    const bool calm =
        s.velocity_world.norm() <= o.rest_speed_mps && rim_speed_mps(i, s) <= o.rest_speed_mps;
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
  // The plane model first: a member alone on the top face or the table; or one about to rest
  // there that no stone touches but that could not rest as it is (held, not balanced).
  for (std::size_t i = 0; i < n; ++i) {
    const MemberContacts& m = step.contacts[i];
    if (!next.active[i] || !m.loaded || m.board != 1) continue;
    const BoardContact& c = m.contact[0];
    const RigidBodyState& s = next.states[i];
    if (m.near > 0 && (m.stones > 0 || m.obstacles > 0 || !calm_for_long(i) ||
                       balanced_on_its_contact(i, s, c) || !clear_of_others(i, next))) {
      continue;
    }
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
  // Who rests here: everyone, or a member no other member is near, calm on the board.
  std::vector<char> resting(n, 0);
  bool to_check = false;  // a member of an island of two or more, or one leaning on an obstacle
  for (std::size_t i = 0; i < n; ++i) {
    if (!next.active[i] || leaving[i]) continue;
    const MemberContacts& m = step.contacts[i];
    resting[i] = all_rest || (m.near == 0 && m.board > 0 && calm_for_long(i));
    if (resting[i] && (members_.size() > 1 || m.stones + m.obstacles > 0)) to_check = true;
  }
  // They rest only where their contacts hold them (options.hold_check); else nobody rests here
  // and the joint solve takes the island on.
  if (to_check && o.hold_check && !o.joint_solve && !held_at_rest(next, h, resting)) {
    resting.assign(n, 0);
    options_.joint_solve = true;  // from the next sub-step on
    ++counters_.hold_failures;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!next.active[i] || leaving[i]) continue;
    const MemberContacts& m = step.contacts[i];
    if (resting[i]) {
      leave(i, NonsmoothEnd::rest);
      continue;
    }
    if (m.near > 0 || m.loaded) continue;
    // Separated: free of the board (exact time of impact) and out of every other member's
    // reach for separation_time_s (a bound: relative speed, rims' speeds, gravity).
    const RigidBodyState& s = next.states[i];
    bool reachable = false;
    for (std::size_t j = 0; j < n && !reachable; ++j) {
      if (j == i || !next.active[j]) continue;
      const RigidBodyState& r = next.states[j];
      const double ts = o.separation_time_s;
      const double reach = (s.velocity_world - r.velocity_world).norm() * ts +
                           (rim_speed_mps(i, s) + rim_speed_mps(j, r)) * ts +
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
  // Nobody left: the states and the active members are the sub-step's, and so is the energy.
  next.energy_j = next.left.empty() ? step.energy_j : energy(next.states, next.active);
  if (!next.left.empty()) {
    // The members still in form the island anew: their totals and energy from here.
    next.anchor.reset();
    next.ceiling_j = next.energy_j;
  } else {
    // The lowest energy so far plus one evaluation's round-off, never above the formation's:
    // the allowance cannot walk upward (the impulses' losses are not won back by round-off).
    next.ceiling_j = std::min(lattice_.ceiling_j, next.energy_j + step.round_off_j);
  }
  narrow_keep_margin(next);
  return next;
}

double NonsmoothIsland::rim_speed_mps(std::size_t i, const RigidBodyState& s) const {
  return members_[i]
             .setup.model.angular_velocity_world(s.orientation, s.angular_momentum_world)
             .norm() *
         members_[i].board.lens().half_width();
}

bool NonsmoothIsland::held_at_rest(const Lattice& l, double h_s,
                                   const std::vector<char>& resting) {
  Lattice trial = l;
  // No energy cap: from rest the fall's potential energy is released in the same sub-step only
  // by the joint solve's corrections, and the guard (step 4) would scale an unpaid start to
  // zero, which is what is asked here.
  trial.energy_j = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < trial.states.size(); ++i) {
    trial.states[i].velocity_world.setZero();
    trial.states[i].angular_momentum_world.setZero();
  }
  // The trial with the joint solve, the option restored however sub_step returns.
  struct Restore {
    bool& option;
    const bool value;
    ~Restore() { option = value; }
  } restore{options_.joint_solve, options_.joint_solve};
  options_.joint_solve = true;
  const Step step = sub_step(trial, h_s, false);
  for (std::size_t i = 0; i < step.states.size(); ++i) {
    if (!resting[i]) continue;
    const RigidBodyState& s = step.states[i];
    const double limit = kHoldSpeedFraction * members_[i].setup.gravity_world.norm() * h_s;
    if (!(s.velocity_world.norm() <= limit) || !(rim_speed_mps(i, s) <= limit)) return false;
  }
  return true;
}

bool NonsmoothIsland::balanced_on_its_contact(std::size_t i, const RigidBodyState& s,
                                              const BoardContact& c) const {
  // On a face across gravity, the weight through G and N = m g at the contact point P balance
  // when the rolling couple can hold the weight's moment about P: |(G - P) across n| <= l_r (as
  // the plane model's rest requires). Elsewhere friction carries part of the weight: not judged.
  const Eigen::Vector3d& g = members_[i].setup.gravity_world;
  const Eigen::Vector3d& n = c.lens.normal_world;
  if (!(-n.dot(g) >= (1.0 - kAcrossGravityTolerance) * g.norm())) return true;
  const Eigen::Vector3d arm = s.position_world - c.lens.point_world;
  const double l_r = (c.on_table() ? table_plastic_ : board_plastic_).rolling_resistance_m;
  return (arm - arm.dot(n) * n).norm() <= l_r + kBalanceToleranceM;
}

bool NonsmoothIsland::clear_of_others(std::size_t i, const Lattice& l) {
  const RigidBodyState& s = l.states[i];
  const LensPose pi = lens_pose(s);
  for (std::size_t j = 0; j < members_.size(); ++j) {
    if (j == i || !l.active[j] ||
        apart_by_bounds(members_[i].board, s, members_[j].board, l.states[j], kLeanGapM)) {
      continue;
    }
    const LensPose pj = lens_pose(l.states[j]);
    if (apart_along_last_normal(i, pi, j, pj, kLeanGapM)) continue;
    if (pair_distance(i, pi, j, pj, true).gap_m <= kLeanGapM) return false;
  }
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    if (obstacle_contact(i, s, o, kLeanGapM, true)) return false;
  }
  return true;
}

void NonsmoothIsland::narrow_keep_margin(Lattice& l) const {
  if (!(options_.keep_s_per_mps > 0.0)) return;
  double kinetic_j = 0.0;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    if (l.active[i]) {
      kinetic_j += std::max(0.0, member_energy(i, l.states[i]) - members_[i].lowest_potential_j);
    }
  }
  double speed_mps = 0.0;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    if (l.active[i]) {
      speed_mps = std::max(speed_mps, point_speed_from_energy(members_[i].setup.model,
                                                              members_[i].board.lens(), kinetic_j));
    }
  }
  // An infinite bound (a member without a lowest potential) keeps the margin; the configured
  // margin is its floor.
  const double keep_m =
      std::max(options_.keep_margin_m, options_.keep_s_per_mps * speed_mps + options_.keep_join_m);
  if (keep_m < l.keep_margin_m) l.keep_margin_m = keep_m;
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
  const double next_j = ahead_->left.empty() ? ahead_->energy_j  // the same members
                                             : energy(ahead_->states, lattice_.active);
  Step partial = sub_step(lattice_, since, false);
  IslandOutcome o;
  o.time_s = t_end_s;
  // Free of the board: as it is when its energy is next_j to round-off. Else the motion beyond
  // the rigid motion that carries the kept totals (kept_totals) scaled, else all of it (on the
  // frictionless board: lattice state k+1 instead, which keeps them).
  const bool free = free_of_board(partial.contacts);
  const double partial_j = partial.energy_j;  // and its round-off, from the sub-step
  const double round_off_j = partial.round_off_j;
  // Free with two members or more, a sample may lie above the previous lattice energy by its
  // round-off, never above the ceiling, as the lattice states may (sub_step, step 4).
  const bool free_allowance =
      free && std::count(lattice_.active.begin(), lattice_.active.end(), 1) > 1;
  auto allowed = [&](double e_j) {
    return e_j <= std::max(lattice_.energy_j, next_j) ||
           (free_allowance && e_j <= lattice_.energy_j + round_off_j && e_j <= lattice_.ceiling_j);
  };
  if (free_allowance && std::abs(partial_j - next_j) <= round_off_j && allowed(partial_j)) {
    o.states = partial.states;
    for (std::size_t i = 0; i < o.states.size(); ++i) {
      if (!lattice_.active[i]) o.states[i] = lattice_.states[i];
    }
    return o;
  }
  std::optional<RigidMotion> rigid;
  bool scaled = false;
  const Kept kept = kept_totals(partial.contacts);
  if (kept != Kept::none) {
    rigid = rigid_motion(partial.states, kept);
    scaled = scale_kinetic_energy(partial.states, next_j, kept);
  }
  // Keeping the horizontal totals, the next lattice state keeps them too (they do not change
  // with time there): it, rather than all of the motion scaled.
  if (!scaled && kept != Kept::horizontal) {
    rigid.reset();
    scaled = scale_kinetic_energy(partial.states, next_j, Kept::none);
  }
  // Round-off can leave it ulps below next_j: grow it back as little as needed
  // (kLargestRoundOffGrowth at most). The growth is bracketed by quadrupling and then bisected, so
  // that the sample ends within round-off above next_j: a sample above it by the quadrupling's
  // overshoot could lie above the next sample (14 ulps, measured with the joint solve).
  if (scaled && energy(partial.states, lattice_.active) < next_j) {
    const std::vector<RigidBodyState> base = partial.states;
    const auto grown = [&](double grow) {
      partial.states = base;
      scale_motion(partial.states, 1.0 + grow, rigid ? &*rigid : nullptr);
      return energy(partial.states, lattice_.active);
    };
    double low = 0.0, high = 1e-15;
    bool reached = grown(high) >= next_j;
    while (!reached && high < kLargestRoundOffGrowth) {
      low = high;
      high = std::min(4.0 * high, kLargestRoundOffGrowth);
      reached = grown(high) >= next_j;
    }
    for (int i = 0; reached && i < kGrowthBisections; ++i) {
      const double middle = 0.5 * (low + high);
      if (middle <= low || middle >= high) break;
      (grown(middle) < next_j ? low : high) = middle;
    }
    if (reached) grown(high);  // else it stays below next_j: the next lattice state (below)
  }
  const double e = energy(partial.states, lattice_.active);
  if (scaled && e >= next_j && allowed(e)) {
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
