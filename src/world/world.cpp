#include "virtual_go/world/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/world/support_plane.h"

namespace virtual_go {
namespace {

// Transitions of one stone at one instant beyond this mean the exact models keep handing the
// contact to each other without progress (a round-off-level standoff): the fallback, which
// always advances time, takes it.
constexpr int kMaxTransitionsAtInstant = 16;
// After a lift-off the stone is in flight when its gap is resolvable (m) and opening.
constexpr double kResolvableGapM = 1e-12;
// A contact found at the very start of a flight after a lift-off, slower than this (m/s), is the
// plane being left, not an impact (the plane model accepts |u_n| up to 1e-6 m/s).
constexpr double kLeavingSpeedMps = 1e-6;
constexpr double kFirstProbeS = 1e-9;
// An approach slower than this (m/s) is a touching state, not an impact: it closes less than the
// 1e-12 m gap resolution in a millisecond. The plane model (or the fallback) removes it by a
// plastic impulse. Physically zero speeds (1e-300 m/s, denormals) are handled here.
constexpr double kTouchingSpeedMps = 1e-9;

}  // namespace

World::World(const WorldConfig& config, const RigidBodyState& initial_state, double t0_s)
    : World(config, std::vector<RigidBodyState>{initial_state}, t0_s) {}

World::World(const WorldConfig& config, const std::vector<RigidBodyState>& initial_states,
             double t0_s)
    : config_((validate_world_config(config), config)),
      broad_phase_(config_.board.spacing_x_m, config_.board.spacing_y_m) {
  // The islands' impacts between stones follow the world's Zeno rule (one source).
  config_.options.nonsmooth.zeno_height_m = config_.zeno_height_m;
  bodies_.emplace_back(WorldBody{config.motion.model, config.shape, std::nullopt},
                       config.motion.gravity_world, config.board);
  reset(initial_states, t0_s);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::check_state(const std::string& field, const WorldBodyModel& body,
                        const RigidBodyState& state) const {
  try {
    (void)state.validated();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(field, field + ": " + e.what());
  }
  if (!config_.board_enabled) return;
  const RigidBodyState s = state.validated();
  const BoardContact c = body.board().nearest(s);
  const double tolerance = config_.options.time_of_impact.touch_tolerance_m;
  if (c.lens.gap_m < -tolerance) {
    throw InvalidArgument(field, field + ": the stone overlaps the " +
                                     (c.on_table() ? std::string("table") : "board") + " (" +
                                     board_feature_name(c.feature) + ") by " +
                                     format_value(-c.lens.gap_m) + " m, at most " +
                                     format_value(tolerance) + " m is allowed");
  }
}

void World::check_time(const std::string& what, double t_s) const {
  require_finite("time", t_s);
  if (t_s < time_) {
    throw InvalidArgument("time", what + " time " + format_value(t_s) +
                                      " s is before the world's time " + format_value(time_) +
                                      " s");
  }
}

void World::check_stone_index(std::size_t stone) const {
  if (stone >= stones_.size()) {
    throw std::out_of_range("stone index " + std::to_string(stone) + " does not exist (" +
                            std::to_string(stones_.size()) + " stones)");
  }
}

void World::reset(const std::vector<RigidBodyState>& states, double t0_s) {
  require_finite("time", t0_s);
  for (std::size_t i = 0; i < states.size(); ++i) {
    check_state(states.size() == 1 ? "state" : "state of stone " + std::to_string(i), bodies_[0],
                states[i]);
  }
  start_stones(states, t0_s);
}

void World::start_stones(const std::vector<RigidBodyState>& states, double t0_s) {
  time_ = t0_s;
  counters_ = WorldCounters{};
  pending_.clear();
  stones_.clear();
  islands_.clear();
  rebuild_broad_phase();
  // Every stone starts awake (in flight); one placed at rest comes to rest at its first advance.
  for (std::size_t k = 0; k < states.size(); ++k) (void)stones_.add(0);
  for (std::size_t i = 0; i < states.size(); ++i) {
    begin_flight(i, states[i].validated(), t0_s, false);
  }
}

const ContactMaterial& World::material_of(const BoardFeature& feature) const {
  return feature.kind == BoardFeatureKind::table ? config_.table_material : config_.board_material;
}

// ---------------------------------------------------------------------------------------------
// Advancing

void World::advance_to(double t_s, std::vector<WorldEvent>& events) {
  (void)advance_to(t_s, events, WorkBudget{});
}

bool World::is_cheap(std::size_t i, double t_s) const {
  const StoneHot& h = stones_.hot(i);
  return h.mode == StoneMode::resting || stones_.record(i).island.has_value() ||
         (h.mode == StoneMode::flight && t_s < h.next_contact_s && t_s <= h.clear_until_s);
}

void World::sample_flight(std::size_t i, double t_s) {
  StoneHot& h = stones_.hot(i);
  if (h.mode != StoneMode::flight) return;  // resting: frozen, no work at all
  if (stones_.record(i).flight.sample(body_at(i).exact(), h.state, h.state_time_s, t_s)) {
    h.state_time_s = t_s;
    ++counters_.flight_steps;
  }
}

AdvanceResult World::advance_to(double t_s, std::vector<WorldEvent>& events,
                                const WorkBudget& budget) {
  require_finite("time", t_s);
  if (t_s < time_) {
    throw InvalidArgument("time", "advance time " + format_value(t_s) +
                                      " s is before the world's time " + format_value(time_) +
                                      " s");
  }
  if (budget.max_steps < 1) {
    throw InvalidArgument("max_steps", "advance work budget max_steps must be at least 1, got " +
                                           std::to_string(budget.max_steps));
  }
  ++counters_.advance_calls;
  const long work_start = counters_.work();
  const bool bounded = budget.max_steps != std::numeric_limits<long>::max();
  bool reached = true;
  // The pipeline (world.h): stages 1-2 find the earliest interaction, stage 3 steps every awake
  // stone to it, stage 4 resolves it; until t_s. A world of one stone, or whose awake stones are
  // far from all others, does one pass.
  int passes_at_instant = 0;
  bool first_pass = true;
  do {
    ++counters_.stages;
    const double before = time_;
    const long wakes_before = counters_.obstacle_wakes;
    long limit = std::numeric_limits<long>::max();
    if (bounded) {
      // A spent budget ends the call between passes, never before the first one's step: every
      // call makes progress, even when one pass's pair search alone costs more than the budget.
      const long left = budget.max_steps - (counters_.work() - work_start);
      if (left < 1 && !first_pass) {
        reached = false;
        break;
      }
      limit = counters_.work() + std::max(1L, left);
    }
    const Interaction next = next_interaction(t_s, limit);  // stages 1 and 2
    if (bounded) limit = std::max(limit, counters_.work() + 1);
    first_pass = false;
    if (!step_stones(next.time_s, limit, bounded)) {  // stage 3
      reached = false;
      break;
    }
    if (time_ == next.time_s) resolve_interaction(next);  // stage 4
    // A pass that ended where an island woke obstacles made progress: the island grew (at most
    // once per stone).
    passes_at_instant =
        time_ == before && counters_.obstacle_wakes == wakes_before ? passes_at_instant + 1 : 0;
    if (passes_at_instant > kMaxTransitionsAtInstant * 4) {
      // A standoff of stone-stone events at one instant (not expected: every impact removes
      // energy and a sustained contact goes to an island): step on without stone contact.
      if (!step_stones(t_s, limit, bounded)) reached = false;
      break;
    }
  } while (time_ < t_s);
  flush(events);
  AdvanceResult result;
  result.reached = reached && time_ == t_s;
  result.time_s = time_;
  result.work = counters_.work() - work_start;
  return result;
}

bool World::step_stones(double t_s, long work_limit, bool bounded) {
  // The stones whose advance costs more than a flight sample (in contact, or meeting a contact
  // before t_s) go first; the cheap ones are sampled at the end, at the time all reached.
  // Only awake stones are looked at; costly ones in stone order (the order the budget is shared
  // in does not depend on the history of the awake list). Island members are moved by their
  // island.
  // Islands go first: a member that leaves (to flight or plane contact) may meet another stone
  // at once, so the pass ends where it leaves and the next pass's pair search sees it.
  double target = t_s;
  advance_islands(target, work_limit);
  std::vector<std::size_t> costly;
  for (const std::size_t i : stones_.awake()) {
    ++counters_.stones_visited;
    if (!is_cheap(i, target)) costly.push_back(i);
  }
  std::sort(costly.begin(), costly.end());
  const long work_start = counters_.work();
  const long max_steps = work_limit - work_start;
  bool stopped = false;
  // With a budget and several costly stones, each one's state before it is advanced: a stone
  // that went past the stop time of a later one is taken back and advanced to that time again.
  struct Snapshot {
    std::size_t stone;
    StoneHot hot;
    StoneRecord record;
  };
  std::vector<Snapshot> snapshots;
  for (std::size_t k = 0; k < costly.size(); ++k) {
    const std::size_t i = costly[k];
    if (bounded && costly.size() > 1)
      snapshots.push_back(Snapshot{i, stones_.hot(i), stones_.record(i)});
    long limit = std::numeric_limits<long>::max();
    if (bounded) {
      const long left = std::max(0L, max_steps - (counters_.work() - work_start));
      const long share = std::max(1L, left / static_cast<long>(costly.size() - k));
      limit = counters_.work() + share;
    }
    if (advance_stone(i, target, limit)) continue;
    stopped = true;
    const double stop = stones_.hot(i).state_time_s;
    if (!(stop < target)) continue;  // stopped at the target itself, with work left there
    target = stop;
    for (std::size_t j = 0; j + 1 < snapshots.size(); ++j) {
      const Snapshot& snap = snapshots[j];
      if (!(stones_.hot(snap.stone).state_time_s > target)) continue;
      stones_.hot(snap.stone) = snap.hot;
      stones_.record(snap.stone) = snap.record;
      stones_.sync_awake(snap.stone);  // it may have come to rest after the snapshot
      pending_.erase(std::remove_if(pending_.begin(), pending_.end(),
                                    [&](const WorldEvent& e) {
                                      return e.stone == snap.stone &&
                                             e.time_s > snap.hot.state_time_s;
                                    }),
                     pending_.end());
      // The same steps as before up to the earlier time: no more work than it already took.
      (void)advance_stone(snap.stone, target, std::numeric_limits<long>::max());
    }
  }
  for (const std::size_t i : stones_.awake()) {
    if (is_cheap(i, target)) sample_flight(i, target);
  }
  time_ = target;
  return !stopped;
}

void World::flush(std::vector<WorldEvent>& events) {
  // Each stone's events are in time order; merge the stones' by time (stable: ties keep the
  // stone order and, within a stone, the order they happened in).
  std::stable_sort(pending_.begin(), pending_.end(), [](const WorldEvent& a, const WorldEvent& b) {
    return a.time_s < b.time_s || (a.time_s == b.time_s && a.stone < b.stone);
  });
  events.insert(events.end(), pending_.begin(), pending_.end());
  pending_.clear();
}

bool World::advance_stone(std::size_t i, double t_s, long work_limit) {
  if (stones_.record(i).island) return true;  // its island moves it (advance_islands)
  // Ahead of t_s (it left an island after another island ended the pass earlier): it waits.
  if (stones_.hot(i).state_time_s > t_s) return true;
  for (;;) {
    StoneHot& h = stones_.hot(i);
    if (h.mode == StoneMode::resting) return true;
    if (counters_.work() >= work_limit) return false;
    bool went_on = false;  // false: a transition happened, go on in the new mode
    switch (h.mode) {
      case StoneMode::resting:
        return true;
      case StoneMode::flight:
        went_on = advance_flight(i, t_s);
        break;
      case StoneMode::plane_contact:
        went_on = advance_plane(i, t_s, work_limit);
        break;
      case StoneMode::nonsmooth_contact:
        went_on = advance_nonsmooth(i, t_s, work_limit);
        break;
    }
    if (went_on)
      return !(stones_.hot(i).state_time_s < t_s) || stones_.hot(i).mode == StoneMode::resting;
  }
}

TimeOfImpact World::search(std::size_t i, double from_s, double to_s) {
  StoneRecord& r = stones_.record(i);
  const TimeOfImpact found =
      board_time_of_impact(body_at(i).board(), body_at(i).setup(), r.flight.anchor(),
                           r.flight.anchor_time_s(), from_s, to_s, config_.options.time_of_impact);
  ++counters_.contact_searches;
  counters_.contact_search_steps += found.advancement_steps + found.polish_steps;
  r.flight.record_search(found);
  stones_.hot(i).next_contact_s = r.flight.contact_time_s();
  stones_.hot(i).clear_until_s = r.flight.clear_until_s();
  return found;
}

bool World::advance_flight(std::size_t i, double t_s) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  // Extend the search only when the flight outlives what is known.
  while (!r.flight.contact() && r.flight.clear_until_s() < t_s) {
    const double from = r.flight.clear_until_s();
    const TimeOfImpact found =
        search(i, from, std::max(t_s, from + config_.options.contact_search_horizon_s));
    if (!found.hit && !(found.time_s > from)) {
      // An exhausted search that could not move (a pathological grazing approach): the
      // fallback takes the stone from there.
      start_nonsmooth(i, found.state, from, WorldEventDetail::edge_contact, nullptr);
      return false;
    }
  }
  if (r.flight.contact() && r.flight.contact()->time_s <= t_s) {
    handle_contact(i);
    return false;
  }
  if (r.flight.sample(body_at(i).exact(), h.state, h.state_time_s, t_s)) {
    h.state_time_s = t_s;
    ++counters_.flight_steps;
  }
  return true;
}

bool World::advance_plane(std::size_t i, double t_s, long work_limit) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  PlaneContactOutcome o;
  try {
    o = r.plane->advance(t_s, std::max(1L, work_limit - counters_.work()));
  } catch (const IntegrationError&) {
    // No consistent contact force (Painleve) or an integrator failure: the fallback takes the
    // contact from the last state handed out, which is exact up to there.
    sync_plane_counters(i);
    start_nonsmooth(i, h.state, h.state_time_s, WorldEventDetail::edge_contact, nullptr);
    return false;
  }
  sync_plane_counters(i);
  h.state = o.state;
  h.state_time_s = o.time_s;
  switch (o.event) {
    case PlaneContactEvent::none:
      return true;
    case PlaneContactEvent::rest:
      come_to_rest(i, o.state, o.time_s, WorldEventDetail::rest);
      return false;
    case PlaneContactEvent::lift_off:
      emit(i, o.time_s, WorldEventKind::lift_off, WorldEventDetail::lift_off, o.state);
      begin_flight(i, o.state, o.time_s, true);
      return false;
    case PlaneContactEvent::left_region:
      start_nonsmooth(i, o.state, o.time_s, WorldEventDetail::left_region, nullptr);
      return false;
    case PlaneContactEvent::obstacle:
      start_nonsmooth(i, o.state, o.time_s, WorldEventDetail::obstacle, nullptr);
      return false;
    default:
      emit(i, o.time_s, plane_regime_kind(o.mode), plane_event_detail(o.event), o.state);
      return false;
  }
}

bool World::advance_nonsmooth(std::size_t i, double t_s, long work_limit) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  const NonsmoothOutcome o = r.nonsmooth->advance(t_s, std::max(1L, work_limit - counters_.work()));
  sync_nonsmooth_counters(i);
  h.state = o.state;
  h.state_time_s = o.time_s;
  switch (o.end) {
    case NonsmoothEnd::none:
      return true;
    case NonsmoothEnd::separated:
      emit(i, o.time_s, WorldEventKind::lift_off, WorldEventDetail::separation, o.state);
      begin_flight(i, o.state, o.time_s, false);
      return false;
    case NonsmoothEnd::plane:
      enter_sustained(i, o.state, o.time_s, o.contact);
      return false;
    case NonsmoothEnd::rest:
      come_to_rest(i, o.state, o.time_s, WorldEventDetail::settle);
      return false;
  }
  return false;
}

// ---------------------------------------------------------------------------------------------
// Transitions

bool World::transition_allowed(std::size_t i, double t_s) {
  StoneRecord& r = stones_.record(i);
  if (t_s != r.transition_time_s) {
    r.transition_time_s = t_s;
    r.transitions_at_instant = 0;
  }
  return ++r.transitions_at_instant <= kMaxTransitionsAtInstant;
}

void World::begin_flight(std::size_t i, const RigidBodyState& state, double t_s,
                         bool after_lift_off) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  if (!transition_allowed(i, t_s)) {
    start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, nullptr);
    return;
  }
  stones_.set_mode(i, StoneMode::flight);
  h.state = state;
  h.state_time_s = t_s;
  r.plane.reset();
  r.nonsmooth.reset();
  r.flight.begin(state, t_s);
  if (!config_.board_enabled) {
    r.flight.set_free_forever();
    h.next_contact_s = r.flight.contact_time_s();
    h.clear_until_s = r.flight.clear_until_s();
    return;
  }
  double from = t_s;
  if (after_lift_off) {
    // The stone leaves its plane with gap, normal velocity and normal force all zero; the gap
    // opens at third order. Find when it is resolvably open (docs/physics.md, "World").
    const ExactMotion flight(body_at(i).setup(), state);
    bool open = false;
    for (double delta = kFirstProbeS; delta <= config_.options.lift_off_probe_s; delta *= 2.0) {
      const RigidBodyState s = flight.state_at(delta);
      const BoardContact c = body_at(i).board().nearest(s);
      if (c.lens.gap_m < -config_.options.time_of_impact.touch_tolerance_m) break;  // closing
      const double rate = c.lens.normal_world.dot(
          point_velocity_world(body_at(i).setup().model, s, c.lens.point_world));
      if (c.lens.gap_m > kResolvableGapM && rate > 0.0) {
        from = t_s + delta;
        open = true;
        break;
      }
    }
    if (!open) {
      // The lift-off was round-off: the contact continues, in the fallback.
      start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, nullptr);
      return;
    }
  }
  search(i, from, from + config_.options.contact_search_horizon_s);
  if (after_lift_off && r.flight.contact() && r.flight.contact()->time_s == from &&
      r.flight.contact()->approach_speed_mps <= kLeavingSpeedMps) {
    start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, nullptr);
  }
}

void World::handle_contact(std::size_t i) {
  const TimeOfImpact c = *stones_.record(i).flight.contact();
  if (!(c.approach_speed_mps > kTouchingSpeedMps)) {
    // Not in flight at all: resting on (or sliding along) the surface already.
    enter_sustained(i, c.state, c.time_s, c.contact);
    return;
  }
  ImpactOptions options;
  options.zeno_height_m = config_.zeno_height_m;
  const Impact impact = resolve_impact(
      body_at(i).setup().model, c.state, c.contact.lens.point_world, c.contact.lens.normal_world,
      material_of(c.contact.feature), body_at(i).setup().gravity_world, options);
  ++counters_.impacts;
  counters_.impact_slip_steps += impact.slip_steps;
  if (impact.frictionless_fallback) ++counters_.impact_fallbacks;
  WorldEvent& e = emit(i, c.time_s, WorldEventKind::impact, WorldEventDetail::impact, impact.state);
  e.has_feature = true;
  e.feature = c.contact.feature;
  e.part = c.contact.lens.part;
  e.energy_change_j = impact.energy_change_j;
  e.approach_speed_mps = -impact.normal_velocity_before_mps;
  e.rebound_speed_mps = impact.normal_velocity_after_mps;
  if (impact.sustained || impact.separating) {
    enter_sustained(i, impact.state, c.time_s, c.contact);
  } else {
    begin_flight(i, impact.state, c.time_s, false);
  }
}

void World::enter_sustained(std::size_t i, const RigidBodyState& state, double t_s,
                            const BoardContact& contact) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  if (!transition_allowed(i, t_s)) {
    start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, &contact);
    return;
  }
  const std::optional<SupportPlane> plane =
      support_plane(body_at(i).board(), contact, lens_pose(state), 0.0);
  if (!plane) {
    start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, &contact);
    return;
  }
  // Exactly onto the plane: the impact or the fallback leaves a gap of round-off size.
  const RigidBodyState on_plane = placed_on_plane(body_at(i).lens(), state, plane->height_m);
  PlaneContactOptions options = config_.options.plane_contact;
  options.clearance_m = support_plane_clearance(body_at(i).board(), *plane);
  try {
    r.plane.emplace(body_at(i).setup().model, body_at(i).lens(), body_at(i).setup().gravity_world,
                    plane->height_m, plane->region, material_of(plane->feature), on_plane, t_s,
                    options);
  } catch (const InvalidArgument&) {
    // The plane model refuses the state (a normal velocity left above its tolerance): the
    // fallback can take any contact.
    r.plane.reset();
    start_nonsmooth(i, state, t_s, WorldEventDetail::edge_contact, &contact);
    return;
  }
  r.nonsmooth.reset();
  r.plane_seen = PlaneContactCounters{};
  stones_.set_mode(i, StoneMode::plane_contact);
  h.state_time_s = t_s;
  if (r.plane->finished()) {
    // At rest at once (or leaving at once): the outcome comes with the first advance.
    h.state = on_plane;
    return;
  }
  h.state = r.plane->state_at(t_s);
  WorldEvent& e =
      emit(i, t_s, plane_regime_kind(r.plane->mode()), WorldEventDetail::contact_start, h.state);
  e.has_feature = true;
  e.feature = plane->feature;
  e.part = r.plane->mode().part;
}

void World::start_nonsmooth(std::size_t i, const RigidBodyState& state, double t_s,
                            WorldEventDetail detail, const BoardContact* contact) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  r.plane.reset();
  r.nonsmooth.emplace(body_at(i).board(), body_at(i).setup(), config_.board_material,
                      config_.table_material, state, t_s, config_.options.nonsmooth,
                      config_.board_enabled);
  r.nonsmooth_seen = NonsmoothCounters{};
  stones_.set_mode(i, StoneMode::nonsmooth_contact);
  h.state = r.nonsmooth->lattice_state();
  h.state_time_s = t_s;
  WorldEvent& e = emit(i, t_s, WorldEventKind::slide, detail, h.state);
  if (!config_.board_enabled) return;  // no board feature to name (an island dissolved in the air)
  const BoardContact c = contact ? *contact : body_at(i).board().nearest(h.state);
  e.has_feature = true;
  e.feature = c.feature;
  e.part = c.lens.part;
}

void World::come_to_rest(std::size_t i, const RigidBodyState& state, double t_s,
                         WorldEventDetail detail) {
  StoneHot& h = stones_.hot(i);
  StoneRecord& r = stones_.record(i);
  stones_.set_mode(i, StoneMode::resting);
  h.state = state;
  h.state_time_s = t_s;
  r.plane.reset();
  r.nonsmooth.reset();
  r.joint_solve = false;  // also after its own fallback (an island dissolved by a command)
  WorldEvent& e = emit(i, t_s, WorldEventKind::rest, detail, state);
  if (config_.board_enabled) {
    const BoardContact c = body_at(i).board().nearest(state);
    e.has_feature = true;
    e.feature = c.feature;
    e.part = c.lens.part;
  }
}

void World::set_state(std::size_t stone, const RigidBodyState& state, double t_s,
                      std::vector<WorldEvent>& events) {
  if (stone >= stones_.size()) {
    throw InvalidArgument("stone", "stone " + std::to_string(stone) + " does not exist (" +
                                       std::to_string(stones_.size()) + " stones)");
  }
  check_time("state", t_s);
  check_state("state", bodies_[stones_.body(stone)], state);
  if (t_s > time_) advance_to(t_s, events);
  const RigidBodyState s = state.validated();
  if (stones_.record(stone).island) dissolve_island(*stones_.record(stone).island, stone);
  if (stones_.hot(stone).mode == StoneMode::resting) {
    emit(stone, t_s, WorldEventKind::wake, WorldEventDetail::wake, s);
  }
  // A command is a new start: the same-instant guard counts from here.
  stones_.record(stone).transition_time_s = -std::numeric_limits<double>::infinity();
  begin_flight(stone, s, t_s, false);
  (void)advance_stone(stone, t_s, std::numeric_limits<long>::max());
  flush(events);
}

// ---------------------------------------------------------------------------------------------
// Bookkeeping

void World::sync_plane_counters(std::size_t i) {
  StoneRecord& r = stones_.record(i);
  const PlaneContactCounters& c = r.plane->counters();
  counters_.plane_contact_steps += c.steps - r.plane_seen.steps;
  counters_.plane_contact_rhs += c.rhs_evaluations - r.plane_seen.rhs_evaluations;
  r.plane_seen = c;
}

void World::sync_nonsmooth_counters(std::size_t i) {
  StoneRecord& r = stones_.record(i);
  add_nonsmooth_work(r.nonsmooth->counters(), r.nonsmooth_seen);
}

void World::add_nonsmooth_work(const NonsmoothCounters& now, NonsmoothCounters& seen) {
  counters_.nonsmooth_steps += now.steps - seen.steps;
  counters_.nonsmooth_impulses += now.impulses - seen.impulses;
  counters_.nonsmooth_frictionless_impulses +=
      now.frictionless_impulses - seen.frictionless_impulses;
  counters_.nonsmooth_energy_scalings += now.energy_guard_scalings - seen.energy_guard_scalings;
  counters_.nonsmooth_holds += now.holds - seen.holds;
  counters_.nonsmooth_joint_solves += now.joint_solves - seen.joint_solves;
  counters_.nonsmooth_joint_iterations += now.joint_iterations - seen.joint_iterations;
  counters_.nonsmooth_joint_capped_solves += now.joint_capped_solves - seen.joint_capped_solves;
  counters_.nonsmooth_hold_failures += now.hold_failures - seen.hold_failures;
  counters_.contact_searches += now.separation_searches - seen.separation_searches;
  seen = now;
}

WorldEvent& World::emit(std::size_t i, double t_s, WorldEventKind kind, WorldEventDetail detail,
                        const RigidBodyState& state) {
  WorldEvent e;
  e.time_s = t_s;
  e.stone = i;
  e.id = stones_.id(i);
  e.kind = kind;
  e.detail = detail;
  e.state = state;
  ++counters_.events;
  pending_.push_back(e);
  return pending_.back();
}

}  // namespace virtual_go
