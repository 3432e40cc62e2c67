// The World's stone-stone contact (docs/physics.md, "World", "Stone-stone contact in the world"):
// stages 1, 2 and 4 of advance_to's pipeline (world.h) and the islands of touching stones. The
// per-stone models (flight, board contact, plane contact, the single-stone fallback) are in
// world.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/pair_gap_bound.h"
#include "virtual_go/contact/pair_impact.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/geometry/lens_pair_distance.h"
#include "virtual_go/world/broad_phase.h"
#include "virtual_go/world/world.h"

namespace virtual_go {
namespace {

// A stone in contact (sliding, the fallback, an island) this close (m) to another stone joins
// one island with it: its motion is not closed form, so the exact time of impact does not
// apply. It is the island's contact margin: a larger one makes members that the island lets go
// (no contact within its margin) rejoin at once, again and again. The conservative steps aim at
// half of it, so they end in a bounded number of passes.
constexpr double kJoinGapM = 1e-9;
// A pair contact approaching slower than this (m/s) is touching, not an impact (as the board's).
constexpr double kPairTouchingSpeedMps = 1e-9;
// A hit's centre-line contact is as good as the search's within this gap (m; the island's gap
// tolerance): then its normal is the one to push along (lens_pair_push_contact).
constexpr double kPairGapToleranceM = 1e-12;
// A stone an island (or the fallback) moves is sampled between its lattice points as a partial
// sub-step with position corrections, or as the next lattice state itself, and a held sub-step
// returns it to the previous lattice pose: within a pass it may jump, not just move at its
// speed bound (a cradle row: 1.3e-7 m into a neighbour within a pass of 6e-9 s). Each of these
// is at most about one sub-step's motion at the speed bound (the corrections remove overlaps
// that one sub-step's motion made); this many sub-steps' worth is taken. An estimate, not a
// proof: measured beyond the speed bound times the pass, at most 0.44 sub-steps' worth (the
// real-board cradle with joins at 1 nm, 1.7 million island advances), 0 with this rule (the
// cradle and test_world_crowd); the overlap checks of those tests watch it.
constexpr double kJumpSubSteps = 2.0;
// An island keeps its members this many times the distance within which the pair search joins
// a stone to it, from its energy at each lattice point (NonsmoothContactOptions::keep_s_per_mps;
// the join distance of a later pass comes from an energy no higher, with the same floors). 2 from
// the energy at formation only held a stone rocking 0.8 mm from its neighbour in the real-board
// cradle's island at h = 3e-4 s (keep 1.7 mm, from the striker's energy) and let it go at
// 1.5e-4 s (0.83 mm): the island stopped its rocking at 0.22 s (it damps rocking: docs/physics.md,
// "A still member stays still"), the plane model at 0.92 s. With the margin narrowed at every
// lattice point, 1.25: 0.917 s at 3e-4, 1.5e-4 and 7.5e-5 s.
constexpr double kKeepJoinFactor = 1.25;

// A pair of closed-form motions touching without approaching is probed this many times over
// the rest of the pass (at halving intervals from its end) for moving into each other.
constexpr int kTouchProbes = 24;

RigidBodyState motion_state(const StoneMotion& m, double t_s) {
  if (m.supported) return m.anchor;
  return ExactMotion(m.setup, m.anchor).state_at(t_s - m.anchor_time_s);
}

// Whether two closed-form motions that touch at from_s without approaching overlap by more than
// overlap_m somewhere in (from_s, to_s]: the exact distance at to_s and at times halving towards
// from_s. A probe, not a bound: the gap's rate is zero at from_s, so it closes at second order
// (surface points turning with the spins), and an overlap that is open at the pass's end but
// not at any probe is missed.
bool moves_into(const StoneMotion& a, const StoneMotion& b, double from_s, double to_s,
                double overlap_m, long& checks) {
  double dt = to_s - from_s;
  for (int k = 0; k < kTouchProbes && dt > 0.0; ++k, dt *= 0.5) {
    const LensPairContact c = lens_pair_distance(a.lens, lens_pose(motion_state(a, from_s + dt)),
                                                 b.lens, lens_pose(motion_state(b, from_s + dt)));
    ++checks;
    if (c.gap_m < -overlap_m) return true;
  }
  return false;
}

}  // namespace

StoneMotion World::stone_motion(std::size_t i) const {
  const StoneHot& h = stones_.hot(i);
  const StoneRecord& r = stones_.record(i);
  const WorldBodyModel& body = body_at(i);
  if (h.mode == StoneMode::flight) {
    return StoneMotion{body.lens(), body.setup(), r.flight.anchor(), r.flight.anchor_time_s(),
                       false};
  }
  return StoneMotion{body.lens(), body.setup(), h.state, h.state_time_s, true};
}

World::IslandRun* World::island_of(std::size_t i) {
  return const_cast<IslandRun*>(static_cast<const World*>(this)->island_of(i));
}

const World::IslandRun* World::island_of(std::size_t i) const {
  const std::optional<std::size_t>& key = stones_.record(i).island;
  if (!key) return nullptr;
  for (const std::unique_ptr<IslandRun>& run : islands_) {
    if (run->key == *key) return run.get();
  }
  return nullptr;
}

namespace {

double point_speed_from_energy(const WorldBodyModel& body, double kinetic_j) {
  return virtual_go::point_speed_from_energy(body.setup().model, body.lens(), kinetic_j);
}

}  // namespace

double World::kinetic_energy_bound(std::size_t k, double dt_s) const {
  KineticBoundMemo* memo = nullptr;
  if (bound_search_ > 0) {
    if (kinetic_memo_.size() < 2 * stones_.size()) kinetic_memo_.resize(2 * stones_.size());
    for (std::size_t slot = 2 * k; slot < 2 * k + 2; ++slot) {
      KineticBoundMemo& m = kinetic_memo_[slot];
      if (m.search == bound_search_ && m.dt_s == dt_s) return m.kinetic_j;
      if (m.search != bound_search_ && !memo) memo = &m;
    }
  }
  const double kinetic_j = kinetic_energy_bound_now(k, dt_s);
  if (memo) *memo = KineticBoundMemo{bound_search_, dt_s, kinetic_j};
  return kinetic_j;
}

double World::kinetic_energy_bound_now(std::size_t k, double dt_s) const {
  return std::max(0.0, energy(k) - lowest_potential(k, dt_s));
}

double World::lowest_potential(std::size_t k, double dt_s) const {
  // Kinetic energy <= energy - the lowest potential: a lens lies at least its half thickness c
  // (its smallest reach) above whatever supports it, the table, or the top face while it cannot
  // leave the face within dt_s even at the table floor's speed bound (gravity taken vertical, as
  // the world's is). Energy never rises in any model, so the bound holds for the whole pass.
  const MotionSetup& setup = body_at(k).setup();
  const LensGeometry& lens = body_at(k).lens();
  const double m = setup.model.mass_properties().mass();
  const double thickness_half = lens.sphere_radius() - lens.sphere_offset();
  const auto at = [&](double floor_z) {
    return -m * setup.gravity_world.z() * (floor_z + thickness_half);
  };
  const double on_table = at(config_.board.table_z_m());
  const Eigen::Vector3d& x = stones_.hot(k).state.position_world;
  const double inside_m = std::min(0.5 * config_.board.size_x_m - std::abs(x.x()),
                                   0.5 * config_.board.size_y_m - std::abs(x.y()));
  const double reach_m =
      lens.half_width() +
      point_speed_from_energy(body_at(k), std::max(0.0, energy(k) - on_table)) * dt_s;
  return x.z() >= config_.board.top_z_m() && inside_m > reach_m ? at(config_.board.top_z_m())
                                                                : on_table;
}

Bounds World::reach_bounds(std::size_t i, double dt_s) const {
  // The lens lies within its rim sphere about the centre, and the centre moves at most at
  // sqrt(2 K / m) with K the kinetic energy bound (its island's, whose members trade energy).
  // In flight this holds across board contacts too, and the flight's swept box up to its board
  // contact lies within this box. Argued, not proven: test_world_reach_bound samples 3000 random
  // stones over a call (flight, bounces, plane contact, rim spin, board edges, islands); the
  // tightest used 0.97 of the motion allowance (a stone sliding on the board).
  const WorldBodyModel& body = body_at(i);
  const double centre_speed = std::sqrt(2.0 * shared_kinetic_energy_bound(i, dt_s) /
                                        body.setup().model.mass_properties().mass());
  // A stone an island or the fallback moves may also jump within a pass (jump_bound).
  return sphere_bounds(stones_.hot(i).state.position_world,
                       body.lens().half_width() + centre_speed * dt_s + jump_bound(i));
}

Bounds World::reach_bounds_of(StoneId id, double dt_s) const {
  const std::size_t i = index_of(id);
  if (!(std::isfinite(dt_s) && dt_s >= 0.0)) {
    throw InvalidArgument("dt", "dt must be finite and >= 0 s, got " + format_value(dt_s));
  }
  return reach_bounds(i, dt_s);
}

double World::shared_kinetic_energy_bound(std::size_t i, double dt_s) const {
  // An island's members may trade energy, so a member gets the island's.
  if (const IslandRun* run = island_of(i)) {
    double kinetic_j = 0.0;
    for (std::size_t k = 0; k < run->members.size(); ++k) {
      if (run->in[k]) kinetic_j += kinetic_energy_bound(index_of(run->members[k]), dt_s);
    }
    return kinetic_j;
  }
  return kinetic_energy_bound(i, dt_s);
}

double World::point_speed_bound(std::size_t i, double dt_s) const {
  return point_speed_from_energy(body_at(i), shared_kinetic_energy_bound(i, dt_s));
}

std::optional<GapBoundMotion> World::gap_bound_motion(std::size_t i, double dt_s) {
  const StoneHot& h = stones_.hot(i);
  if (h.mode == StoneMode::resting) return still_motion();
  if (stones_.record(i).island) return std::nullopt;  // impulses: no force bound
  const WorldBodyModel& body = body_at(i);
  const MotionModel& model = body.setup().model;
  const Eigen::Vector3d omega =
      model.angular_velocity_world(h.state.orientation, h.state.angular_momentum_world);
  if (h.mode == StoneMode::flight) {
    // The pass ends at the flight's board contact (stage 1), so no impulse within it.
    return flight_motion(model, h.state.velocity_world, omega,
                         std::numeric_limits<double>::infinity());
  }
  if (h.mode != StoneMode::plane_contact) return std::nullopt;
  // On the top face only (the table's contact may meet the board's sides: an obstacle), with
  // gravity vertical, and while the contact point cannot leave the face.
  const Eigen::Vector3d& g = body.setup().gravity_world;
  const Eigen::Vector3d& x = h.state.position_world;
  if (!(x.z() >= config_.board.top_z_m()) || g.x() != 0.0 || g.y() != 0.0) return std::nullopt;
  const double kinetic_j = kinetic_energy_bound(i, dt_s);
  const LensPose pose = lens_pose(h.state);
  const std::optional<PlaneCapForceBound> cap =
      plane_cap_force_bound(model, body.lens(), config_.board_material, -g.z(), pose.axis_world,
                            h.state.velocity_world, omega, kinetic_j);
  if (!cap) return std::nullopt;
  GapBoundMotion motion = cap->motion;
  // The contact point lies within the rim radius of the centre; it stays on the face while the
  // centre is farther than that from the face's edges.
  const double inside_m = std::min(0.5 * config_.board.size_x_m - std::abs(x.x()),
                                   0.5 * config_.board.size_y_m - std::abs(x.y()));
  const double speed = point_speed_from_energy(body, kinetic_j);
  const double room_m = inside_m - body.lens().half_width();
  if (!(room_m > 0.0)) return std::nullopt;
  if (speed > 0.0) motion.valid_for_s = std::min(motion.valid_for_s, room_m / speed);
  return motion;
}

double World::second_order_step(std::size_t i, std::size_t j, const LensPairContact& c, double dt_s,
                                double level_m) {
  const std::optional<GapBoundMotion> mi = gap_bound_motion(i, dt_s);
  if (!mi) return 0.0;
  const std::optional<GapBoundMotion> mj = gap_bound_motion(j, dt_s);
  if (!mj) return 0.0;
  const StoneHot& hi = stones_.hot(i);
  const StoneHot& hj = stones_.hot(j);
  const PairGapBound bound(body_at(i).lens(), lens_pose(hi.state), *mi, body_at(j).lens(),
                           lens_pose(hj.state), *mj, c.normal_world,
                           body_at(j).setup().gravity_world - body_at(i).setup().gravity_world);
  return bound.time_to(level_m);
}

double World::jump_bound(std::size_t i) const {
  if (stones_.hot(i).mode != StoneMode::nonsmooth_contact) return 0.0;
  // Over the jump's own span: a stone that cannot leave the top face within it has the face as
  // its floor (the table's would count the board's thickness as energy: a full board's island
  // grew with every row it reached at the edge and swallowed the board).
  const double span_s = kJumpSubSteps * config_.options.nonsmooth.step_s;
  return point_speed_bound(i, span_s) * span_s;
}

void World::enter_fallen_asleep() {
  // Every stone that came to rest since the last pass: its rim sphere, resting (a stone woken
  // again since is entered as awake by the pair search).
  for (const std::size_t i : stones_.take_fallen_asleep()) {
    if (!config_.stone_contact || stones_.hot(i).mode != StoneMode::resting) continue;
    broad_phase_.update(
        i, sphere_bounds(stones_.hot(i).state.position_world, body_at(i).lens().half_width()),
        false);
  }
}

void World::rebuild_broad_phase() {
  broad_phase_ = BroadPhase(config_.board.spacing_x_m, config_.board.spacing_y_m);
  (void)stones_.take_fallen_asleep();
  if (!config_.stone_contact) return;
  for (std::size_t i = 0; i < stones_.size(); ++i) {
    if (stones_.hot(i).mode != StoneMode::resting) continue;  // entered by the next pair search
    broad_phase_.update(
        i, sphere_bounds(stones_.hot(i).state.position_world, body_at(i).lens().half_width()),
        false);
  }
}

World::Interaction World::next_interaction(double t_s, long work_limit) {
  Interaction next;
  next.time_s = t_s;
  enter_fallen_asleep();
  // From here to the return no stone's state changes: the kinetic energy bounds are memoised.
  struct BoundSearch {
    long& current;
    BoundSearch(long& c, long& count) : current(c) { current = ++count; }
    ~BoundSearch() { current = 0; }
  } bound_search(bound_search_, bound_searches_);
  if (!config_.stone_contact || stones_.size() < 2 || stones_.all_resting()) return next;
  const auto consider = [&](double time_s, Interaction::Kind kind, std::size_t a, std::size_t b,
                            const PairTimeOfImpact* hit) {
    // Impacts at one instant (touching stones struck together): the fastest approach first, the
    // rule of contact/simultaneous_impacts.h (ties: the pair search's order).
    const bool faster = time_s == next.time_s && kind == Interaction::Kind::impact &&
                        next.kind == Interaction::Kind::impact && hit &&
                        hit->approach_speed_mps > next.hit.approach_speed_mps;
    if (time_s < next.time_s || faster ||
        (time_s == next.time_s && kind != Interaction::Kind::none &&
         next.kind == Interaction::Kind::none)) {
      next.time_s = time_s;
      next.kind = kind;
      next.a = a;
      next.b = b;
      if (hit) next.hit = *hit;
    }
  };
  std::vector<std::size_t> awake(stones_.awake().begin(), stones_.awake().end());
  std::sort(awake.begin(), awake.end());
  const double dt = t_s - time_;
  const auto is_awake = [&](std::size_t k) { return stones_.hot(k).mode != StoneMode::resting; };

  // Stage 1a, stones alone: an awake stone (not in an island) whose reach over the whole call
  // meets no other stone's bounds (a resting stone's rim sphere, an awake stone's reach) cannot
  // touch another stone before t_s. Its board events need not end the pass: step_stones takes
  // it through them like a stone of a world without stone contact. Otherwise every bounce of
  // every stone would end a pass that visits every awake stone, and an event would cost O(N).
  // The reach keeps standing for it in the broad phase, so no later candidate pair names it
  // (every bound of stage 1b lies within the stone's reach).
  // Only the awake stones' entries are written and read: a resting stone's is never looked at
  // (no O(stones) clearing per pass).
  alone_.resize(stones_.size());
  for (const std::size_t i : awake) {
    alone_[i] = stones_.record(i).island ? 0 : 1;
    broad_phase_.update(i, reach_bounds(i, dt), true);
  }
  {
    const long tests_before = broad_phase_.counters().bound_tests;
    for (const auto& pair : broad_phase_.candidate_pairs()) {
      alone_[pair.first] = 0;
      alone_[pair.second] = 0;
    }
    counters_.broad_phase_tests += broad_phase_.counters().bound_tests - tests_before;
  }

  // Stage 1b, board search of the other stones: each flight's board contact up to t_s (as
  // advance_flight does); the flight is closed form up to there. The pass stops at it: the
  // flight after the bounce is searched against the other stones in the next pass. Each such
  // stone's bounds for the pass go into the broad phase (resting stones are in it already).
  flight_end_.resize(stones_.size());
  for (const std::size_t i : awake) {
    if (alone_[i]) continue;
    StoneHot& h = stones_.hot(i);
    StoneRecord& r = stones_.record(i);
    const double rim_m = body_at(i).lens().half_width();
    flight_end_[i] = t_s;
    if (h.mode == StoneMode::flight) {
      if (config_.board_enabled) {
        while (!r.flight.contact() && r.flight.clear_until_s() < t_s) {
          const double from = r.flight.clear_until_s();
          const TimeOfImpact found =
              search(i, from, std::max(t_s, from + config_.options.contact_search_horizon_s));
          if (!found.hit && !(found.time_s > from)) break;  // advance_flight hands it over
        }
        if (r.flight.contact()) flight_end_[i] = std::min(t_s, r.flight.contact()->time_s);
        if (r.flight.clear_until_s() < flight_end_[i] && !r.flight.contact())
          flight_end_[i] = std::max(time_, r.flight.clear_until_s());
      }
      consider(flight_end_[i], Interaction::Kind::none, 0, 0, nullptr);
      broad_phase_.update(i,
                          swept_bounds(h.state.position_world, h.state.velocity_world,
                                       body_at(i).setup().gravity_world,
                                       std::max(0.0, flight_end_[i] - time_), rim_m),
                          true);
    } else {
      broad_phase_.update(i, reach_bounds(i, dt), true);
    }
  }

  // Stage 2, pair search: the broad phase's candidates (awake-awake and awake-resting pairs
  // whose bounds meet; never two resting stones), in index order. Closed-form motions both: the
  // exact time of impact. A stone in contact: the gap closes at most at the sum of the point
  // speed bounds.
  const long tests_before = broad_phase_.counters().bound_tests;
  const std::vector<std::pair<std::size_t, std::size_t>> pairs = broad_phase_.candidate_pairs();
  counters_.broad_phase_tests += broad_phase_.counters().bound_tests - tests_before;
  counters_.pair_candidates += static_cast<long>(pairs.size());
  const PairTimeOfImpactOptions full_search;
  // Resting stones within an island member's reach: the island's obstacles (below).
  struct ObstacleClaim {
    std::size_t stone, island, member;
  };
  std::vector<ObstacleClaim> claims;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto& pair = pairs[p];
    // i is awake; j is the other (awake with a larger index, or resting).
    const std::size_t i = is_awake(pair.first) ? pair.first : pair.second;
    const std::size_t j = i == pair.first ? pair.second : pair.first;
    const StoneRecord& ri = stones_.record(i);
    const StoneRecord& rj = stones_.record(j);
    if (ri.island && rj.island && *ri.island == *rj.island) continue;
    const StoneHot& hi = stones_.hot(i);
    const StoneHot& hj = stones_.hot(j);
    const bool closed_i = hi.mode == StoneMode::flight;
    const bool closed_j = hj.mode == StoneMode::flight || hj.mode == StoneMode::resting;
    if (closed_i && closed_j) {
      const double end = std::min(flight_end_[i], is_awake(j) ? flight_end_[j] : t_s);
      // The search's share of the work left (at least one step; a search exhausted by its
      // share is contact-free up to where it got, which ends the pass there).
      PairTimeOfImpactOptions options = full_search;
      const long share = (work_limit - counters_.work()) / static_cast<long>(pairs.size() - p);
      options.max_steps = static_cast<int>(std::clamp(share, 1L, long{full_search.max_steps}));
      PairTimeOfImpact hit =
          pair_time_of_impact(stone_motion(i), stone_motion(j), time_, end, options);
      if (hit.exhausted && !(hit.time_s > time_) && options.max_steps < full_search.max_steps) {
        // No progress within the share: the full search, one indivisible unit (world.h).
        counters_.pair_search_steps += hit.advancement_steps + hit.polish_steps;
        hit = pair_time_of_impact(stone_motion(i), stone_motion(j), time_, end, full_search);
      }
      ++counters_.pair_searches;
      counters_.pair_search_steps += hit.advancement_steps + hit.polish_steps;
      // A hit at the instant a member meets the board is left to the next pass (the board
      // contact comes first there).
      const auto board_by = [&](std::size_t k) {
        return stones_.hot(k).mode == StoneMode::flight && stones_.record(k).flight.contact() &&
               stones_.record(k).flight.contact()->time_s <= end;
      };
      if (hit.hit && !(hit.approach_speed_mps > kPairTouchingSpeedMps) &&
          hit.approach_speed_mps > -kPairTouchingSpeedMps &&
          !moves_into(stone_motion(i), stone_motion(j), hit.time_s, end, 0.5 * kJoinGapM,
                      counters_.pair_gap_checks)) {
        // Touching without approaching, and not moving into each other within the pass (a row
        // flying together face to face): not an interaction in this pass. Moving into each
        // other (the end of a run of ever slower impacts between spinning stones; a stone
        // sliding down past a neighbour it touches) is sustained contact: collide_pair makes an
        // island of it (let be, the two sank into each other within the pass).
        continue;
      }
      if (hit.hit && (hit.time_s < end || !(board_by(i) || board_by(j)))) {
        consider(hit.time_s, Interaction::Kind::impact, i, j, &hit);
      } else if (hit.exhausted && !(hit.time_s > time_)) {
        consider(time_, Interaction::Kind::join, i, j, nullptr);  // no progress: the island
      } else if (hit.exhausted) {
        consider(hit.time_s, Interaction::Kind::none, 0, 0, nullptr);
      }
      continue;
    }
    const LensPairContact c = lens_pair_distance(body_at(i).lens(), lens_pose(hi.state),
                                                 body_at(j).lens(), lens_pose(hj.state));
    ++counters_.pair_gap_checks;
    if (ri.island && hj.mode == StoneMode::resting) {
      // A resting stone an island member can reach within the pass (its motion over the pass at
      // the point-speed bound, twice its jump, the join margin) is the island's obstacle: kept
      // out of, not moved, woken only when the island acts on it (advance_island). Farther ones
      // bound the pass as before (first_order below: beyond the pass).
      const double within_m = kJoinGapM + 2.0 * jump_bound(i) + point_speed_bound(i, dt) * dt;
      if (c.gap_m <= within_m) {
        claims.push_back(ObstacleClaim{j, *ri.island, i});
        continue;
      }
    }
    // A stone an island or the fallback moves may jump within the pass (jump_bound): it joins
    // the stones within twice its jump (and the join margin), which the island then keeps
    // (form_island), and the steps below keep that far from the others. (An island's resting
    // neighbours are its obstacles instead, above.)
    const bool impulsive =
        hi.mode == StoneMode::nonsmooth_contact || hj.mode == StoneMode::nonsmooth_contact;
    const double reach = jump_bound(i) + (is_awake(j) ? jump_bound(j) : 0.0);
    if (impulsive && c.gap_m <= kJoinGapM + 2.0 * reach) {
      // Approaching or not: a stone an island pushes can start to approach its neighbour at
      // any instant of the pass (let be, it was pushed into the neighbour within the pass).
      consider(time_, Interaction::Kind::join, i, j, nullptr);
      continue;
    }
    if (c.gap_m <= kJoinGapM) {
      // Touching: one island when they approach at the witness points or overlap. Touching
      // without approaching (sliding past, rocking side by side) it is let be while the
      // second-order bound keeps the overlap below half the join margin, and the pass ends
      // there; without that bound, one island.
      const Eigen::Vector3d u_i =
          point_velocity_world(body_at(i).setup().model, hi.state, c.point_a_world);
      const Eigen::Vector3d u_j =
          point_velocity_world(body_at(j).setup().model, hj.state, c.point_b_world);
      if (c.normal_world.dot(u_j - u_i) < -kPairTouchingSpeedMps || c.gap_m < -kJoinGapM) {
        consider(time_, Interaction::Kind::join, i, j, nullptr);
        continue;
      }
      const double let_be = second_order_step(i, j, c, dt, -0.5 * kJoinGapM);
      if (!(let_be > 0.0)) {
        consider(time_, Interaction::Kind::join, i, j, nullptr);
      } else if (let_be < std::numeric_limits<double>::infinity()) {
        consider(time_ + let_be, Interaction::Kind::none, 0, 0, nullptr);
      }
      continue;
    }
    // The later of two guaranteed times: the first-order one (the gap closes at most at the sum
    // of the point-speed bounds, less the jumps) and the second-order one
    // (contact/pair_gap_bound.h: the exact present rate and bounded accelerations; a pair sliding
    // side by side goes ~sqrt(gap); not for a stone that jumps).
    const double rate = point_speed_bound(i, dt) + (is_awake(j) ? point_speed_bound(j, dt) : 0.0);
    const double first_order = rate > 0.0 ? (c.gap_m - 0.5 * kJoinGapM - reach) / rate
                                          : std::numeric_limits<double>::infinity();
    const double step =
        std::max(first_order, impulsive ? 0.0 : second_order_step(i, j, c, dt, 0.5 * kJoinGapM));
    if (step < std::numeric_limits<double>::infinity()) {
      consider(time_ + step, Interaction::Kind::none, 0, 0, nullptr);
    }
  }
  // An obstacle belongs to one island: a resting stone that two islands can reach joins them
  // (either may wake it; the other would go on keeping out of where it was).
  const auto by_stone = [](const ObstacleClaim& x, const ObstacleClaim& y) {
    return x.stone != y.stone ? x.stone < y.stone : x.island < y.island;
  };
  std::sort(claims.begin(), claims.end(), by_stone);
  for (std::size_t k = 1; k < claims.size(); ++k) {
    if (claims[k].stone == claims[k - 1].stone && claims[k].island != claims[k - 1].island)
      consider(time_, Interaction::Kind::join, claims[k - 1].member, claims[k].member, nullptr);
  }
  // Each island's obstacles for this pass (none when no resting stone is within reach).
  for (const std::unique_ptr<IslandRun>& run : islands_) {
    std::vector<IslandObstacle> obstacles;
    run->obstacles.clear();
    for (std::size_t k = 0; k < claims.size(); ++k) {
      if (claims[k].island != run->key) continue;
      if (k > 0 && claims[k - 1].stone == claims[k].stone && claims[k - 1].island == run->key)
        continue;  // claimed by two members
      const std::size_t j = claims[k].stone;
      run->obstacles.push_back(stones_.id(j));
      obstacles.push_back(IslandObstacle{body_at(j).lens(), stones_.hot(j).state});
    }
    run->island.set_obstacles(std::move(obstacles));
  }
  return next;
}

void World::resolve_interaction(const Interaction& next) {
  switch (next.kind) {
    case Interaction::Kind::none:
      return;
    case Interaction::Kind::impact:
      collide_pair(next.a, next.b, next.hit);
      return;
    case Interaction::Kind::join:
      form_island({next.a, next.b}, {}, time_);
      return;
  }
}

void World::collide_pair(std::size_t a, std::size_t b, const PairTimeOfImpact& hit) {
  const double t = hit.time_s;
  const bool a_rests = stones_.hot(a).mode == StoneMode::resting;
  const bool b_rests = stones_.hot(b).mode == StoneMode::resting;
  if (a_rests)
    emit(a, t, WorldEventKind::wake, WorldEventDetail::wake, hit.state_a).other = stones_.id(b);
  if (b_rests)
    emit(b, t, WorldEventKind::wake, WorldEventDetail::wake, hit.state_b).other = stones_.id(a);
  if (!(hit.approach_speed_mps > kPairTouchingSpeedMps)) {
    // Touching (or overlapping within the tolerance) without an approach: sustained.
    form_island({a, b}, {hit.state_a, hit.state_b}, t);
    return;
  }
  ImpactOptions options;
  options.zeno_height_m = config_.zeno_height_m;
  // The normal to push along (lens_pair_distance.h): two flat stones meeting rim to rim in one
  // plane touch along every tilt of the rims' fans, and the search's pick among them is
  // round-off (measured: 0.05 deg to 29 deg for the same collision started at other distances).
  // Taken only while the stones approach along it, as along the search's normal.
  const MotionModel& model_a = body_at(a).setup().model;
  const MotionModel& model_b = body_at(b).setup().model;
  LensPairContact contact =
      lens_pair_push_contact(body_at(a).lens(), lens_pose(hit.state_a), body_at(b).lens(),
                             lens_pose(hit.state_b), hit.contact, kPairGapToleranceM);
  const auto approach_along = [&](const LensPairContact& c) {
    const Eigen::Vector3d point = 0.5 * (c.point_a_world + c.point_b_world);
    return -c.normal_world.dot(point_velocity_world(model_b, hit.state_b, point) -
                               point_velocity_world(model_a, hit.state_a, point));
  };
  if (!(approach_along(contact) > kPairTouchingSpeedMps)) contact = hit.contact;
  const Eigen::Vector3d point_world = 0.5 * (contact.point_a_world + contact.point_b_world);
  const PairImpact p = resolve_pair_impact(model_a, hit.state_a, model_b, hit.state_b, point_world,
                                           contact.normal_world, config_.stone_material, options);
  ++counters_.impacts;
  ++counters_.pair_impacts;
  counters_.impact_slip_steps += p.slip_steps;
  if (p.frictionless_fallback) ++counters_.impact_fallbacks;
  const auto impact_event = [&](std::size_t i, std::size_t other, const RigidBodyState& state,
                                LensPart part) {
    WorldEvent& e = emit(i, t, WorldEventKind::impact, WorldEventDetail::impact, state);
    e.other = stones_.id(other);
    e.part = part;
    e.energy_change_j = p.energy_change_j;  // the pair's, on both events
    e.approach_speed_mps = -p.normal_velocity_before_mps;
    e.rebound_speed_mps = p.normal_velocity_after_mps;
  };
  impact_event(a, b, p.state_a, contact.part_a);
  impact_event(b, a, p.state_b, contact.part_b);
  // A rebound below the Zeno rule's speed (docs/physics.md, "Impact"), or a partner that was
  // resting (held by the board, which this two-body impact leaves out): the contact is
  // sustained, the island takes it.
  const double zeno_speed_mps =
      std::sqrt(2.0 * config_.motion.gravity_world.norm() * config_.zeno_height_m);
  const bool sustained = config_.board_enabled &&
                         (a_rests || b_rests || !(p.normal_velocity_after_mps > zeno_speed_mps));
  if (sustained) {
    form_island({a, b}, {p.state_a, p.state_b}, t);
    return;
  }
  begin_flight(a, p.state_a, t, false);
  begin_flight(b, p.state_b, t, false);
}

void World::form_island(const std::vector<std::size_t>& seeds,
                        const std::vector<RigidBodyState>& states, double t_s) {
  std::vector<std::size_t> members;
  std::vector<RigidBodyState> initial;
  const auto add = [&](std::size_t i, const RigidBodyState& s) {
    if (std::find(members.begin(), members.end(), i) != members.end()) return;
    members.push_back(i);
    initial.push_back(s);
  };
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const std::size_t seed = seeds[k];
    if (IslandRun* run = island_of(seed)) {
      // Its island joins whole, from the members' present states.
      for (std::size_t m = 0; m < run->members.size(); ++m) {
        if (!run->in[m]) continue;
        const std::size_t i = index_of(run->members[m]);
        stones_.record(i).island.reset();
        add(i, stones_.hot(i).state);
      }
      const std::size_t key = run->key;
      islands_.erase(
          std::remove_if(islands_.begin(), islands_.end(),
                         [&](const std::unique_ptr<IslandRun>& r) { return r->key == key; }),
          islands_.end());
    } else {
      add(seed, states.empty() ? stones_.hot(seed).state : states[k]);
    }
  }
  // The island keeps its members within kKeepJoinFactor times the distance the pair search
  // joins at (2 jumps and the margin), from the members' energy above each one's floor at
  // formation, narrowed as that energy falls (NonsmoothContactOptions::keep_s_per_mps).
  NonsmoothContactOptions options = config_.options.nonsmooth;
  for (const std::size_t i : members) {
    if (stones_.record(i).joint_solve) options.joint_solve = true;
  }
  const double span_s = kJumpSubSteps * options.step_s;  // as jump_bound
  options.keep_s_per_mps = kKeepJoinFactor * 2.0 * span_s;
  options.keep_join_m = kKeepJoinFactor * kJoinGapM;
  std::vector<IslandBody> bodies;
  std::vector<StoneId> ids;
  for (std::size_t k = 0; k < members.size(); ++k) {
    bodies.push_back(IslandBody{body_at(members[k]).board(), body_at(members[k]).setup(),
                                initial[k], config_.board_enabled,
                                lowest_potential(members[k], span_s)});
    ids.push_back(stones_.id(members[k]));
  }
  auto run = std::make_unique<IslandRun>(
      IslandRun{next_island_key_++,
                NonsmoothIsland(std::move(bodies), config_.board_material, config_.table_material,
                                config_.stone_material, t_s, options),
                ids,
                std::vector<char>(members.size(), 1),
                NonsmoothCounters{},
                {},
                {}});
  ++counters_.islands_formed;
  counters_.largest_island = std::max(counters_.largest_island, static_cast<long>(members.size()));
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::size_t i = members[k];
    StoneHot& h = stones_.hot(i);
    StoneRecord& r = stones_.record(i);
    if (r.plane) {
      sync_plane_counters(i);
      r.plane.reset();
    }
    if (r.nonsmooth) {
      sync_nonsmooth_counters(i);
      r.nonsmooth.reset();
    }
    const std::size_t partner = members[k == 0 && members.size() > 1 ? 1 : 0];
    // A resting stone hit by an impact was woken by it; one touched by a stone in contact is
    // woken here.
    if (h.mode == StoneMode::resting && states.empty()) {
      emit(i, t_s, WorldEventKind::wake, WorldEventDetail::wake, h.state).other =
          stones_.id(partner);
    }
    stones_.set_mode(i, StoneMode::nonsmooth_contact);
    h.state = run->island.lattice_state(k);
    h.state_time_s = t_s;
    r.island = run->key;
    WorldEvent& e = emit(i, t_s, WorldEventKind::slide, WorldEventDetail::stone_contact, h.state);
    if (partner != i) e.other = stones_.id(partner);
  }
  islands_.push_back(std::move(run));
}

void World::advance_islands(double& t_s, long work_limit) {
  // By key order (the order they were formed): deterministic.
  for (std::size_t k = 0; k < islands_.size(); ++k) {
    IslandRun& run = *islands_[k];
    const auto first = std::find(run.in.begin(), run.in.end(), 1);
    if (first == run.in.end()) continue;
    const std::size_t any = index_of(run.members[static_cast<std::size_t>(first - run.in.begin())]);
    if (!(stones_.hot(any).state_time_s < t_s)) continue;  // ahead already (see world.h)
    t_s = std::min(t_s, advance_island(run, t_s, work_limit));
  }
  islands_.erase(std::remove_if(islands_.begin(), islands_.end(),
                                [](const std::unique_ptr<IslandRun>& r) {
                                  return std::find(r->in.begin(), r->in.end(), 1) == r->in.end();
                                }),
                 islands_.end());
  // Islands that woke obstacles: formed anew with them, at the lattice time where they stopped
  // (by key order; an obstacle belongs to one island, so these are distinct stones).
  std::vector<std::vector<std::size_t>> redo;
  for (const std::unique_ptr<IslandRun>& run : islands_) {
    if (run->woken.empty()) continue;
    std::vector<std::size_t> seeds;
    for (std::size_t m = 0; m < run->members.size() && seeds.empty(); ++m) {
      if (run->in[m]) seeds.push_back(index_of(run->members[m]));
    }
    seeds.insert(seeds.end(), run->woken.begin(), run->woken.end());
    run->woken.clear();
    redo.push_back(std::move(seeds));
  }
  for (const std::vector<std::size_t>& seeds : redo) {
    form_island(seeds, {}, stones_.hot(seeds.front()).state_time_s);
  }
}

double World::advance_island(IslandRun& run, double t_s, long work_limit) {
  for (;;) {
    const IslandOutcome o = run.island.advance(t_s, std::max(1L, work_limit - counters_.work()));
    add_nonsmooth_work(run.island.counters(), run.seen);
    const bool joint = run.island.options().joint_solve;
    for (std::size_t m = 0; m < run.members.size(); ++m) {
      if (!run.in[m]) continue;
      const std::size_t i = index_of(run.members[m]);
      StoneHot& h = stones_.hot(i);
      h.state = o.states[m];
      h.state_time_s = o.time_s;
      stones_.record(i).joint_solve = joint;
    }
    // Members leave as the single-stone fallback's stone does (advance_nonsmooth).
    for (const IslandMemberEnd& end : o.left) {
      run.in[end.member] = 0;
      const std::size_t i = index_of(run.members[end.member]);
      stones_.record(i).island.reset();
      stones_.record(i).joint_solve = false;
      const RigidBodyState& s = o.states[end.member];
      switch (end.end) {
        case NonsmoothEnd::separated:
          emit(i, o.time_s, WorldEventKind::lift_off, WorldEventDetail::separation, s);
          begin_flight(i, s, o.time_s, false);
          break;
        case NonsmoothEnd::plane:
          enter_sustained(i, s, o.time_s, end.contact);
          break;
        case NonsmoothEnd::rest:
        case NonsmoothEnd::none:
          come_to_rest(i, s, o.time_s, WorldEventDetail::settle);
          break;
      }
    }
    if (!o.woken.empty()) {
      // It acted on resting stones: they wake, and the island is formed anew with them where it
      // is (advance_islands), to redo that sub-step; the pass ends here, so the other stones'
      // pair searches see them awake in the next pass.
      for (const std::size_t k : o.woken) run.woken.push_back(index_of(run.obstacles[k]));
      counters_.obstacle_wakes += static_cast<long>(o.woken.size());
      return o.time_s;
    }
    if (!o.left.empty() || o.finished || !(o.time_s < t_s) || counters_.work() >= work_limit)
      return o.time_s;
  }
}

void World::dissolve_island(std::size_t key, std::size_t except) {
  // A command on a member: the others go on each in its own fallback (the island of one); they
  // rejoin at the next pass where they touch.
  for (std::size_t k = 0; k < islands_.size(); ++k) {
    IslandRun& run = *islands_[k];
    if (run.key != key) continue;
    for (std::size_t m = 0; m < run.members.size(); ++m) {
      if (!run.in[m]) continue;
      const std::size_t i = index_of(run.members[m]);
      stones_.record(i).island.reset();
      if (i == except) continue;  // the commanded stone: the command gives its state
      start_nonsmooth(i, stones_.hot(i).state, stones_.hot(i).state_time_s,
                      WorldEventDetail::stone_contact, nullptr);
    }
    islands_.erase(islands_.begin() + static_cast<std::ptrdiff_t>(k));
    return;
  }
}

}  // namespace virtual_go
