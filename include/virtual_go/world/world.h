// Stones on a Go board standing on a table (docs/physics.md, "World"). advance_to(t) takes every
// stone to the time t through all its events in time order: exact flight in closed form, exact
// times of impact, impacts that cannot add energy, sustained contact on the top face or the table
// in coordinates where the stone can neither sink nor float, a fixed-step nonsmooth fallback for
// edges, corners and sides, and exact rest. After the call state(i) is the state at t; each event
// carries the exact state at its own instant. A caller sampling a fixed grid (the node, a
// benchmark) calls advance_to at every grid time and reads the states.
//
// Cost: a flying stone costs one exact-integrator step per call (two quaternion products on a
// fixed grid) and a comparison with its cached contact time, searched once per flight; a stone in
// contact costs its contact model's steps; a resting stone costs nothing: it is not even looked
// at (the world keeps the list of awake stones, as Box2D v3 keeps its awake set, so a call costs
// the same with 0 or 361 resting stones), its pose frozen bit for bit, until a command wakes it.
// Stones touch (docs/physics.md, "World", "Stone-stone contact in the world"): advance_to is a
// pipeline of named stages repeated until t: (1a) stones alone: a stone (not in an island)
// whose reach over the whole call meets no other stone's bounds goes through its own events in
// step 3 without ending a pass, so an event costs the same among 1 or 361 stones far apart;
// (1b) board search: each other flight's board contact is known up to t; (2) pair search: every
// awake stone against every other stone within the reach its energy allows (world/broad_phase's
// grid: awake-awake and awake-resting pairs only, never two resting stones; resting stones enter it
// when they come to rest): a flight against a flight or a resting stone by the exact pair time of
// impact (closed form both), any pair with a stone in contact (sliding, fallback, island)
// conservatively (the gap can close at most at the sum of the point speeds their energies allow);
// (3) step: every awake stone to the earliest of the first pair contact, the first board contact of
// a flight near another stone, the conservative safe time and t (the per-stone models, as before);
// (4) resolve there: a pair impact (Stronge, the config's stone_material; both stones get an
// `impact` naming the other; a resting stone hit gets a `wake` first), or, for a sustained contact
// (a resting or touching partner, a rebound below the Zeno speed, a stone in contact within 1 nm of
// another), one NonsmoothIsland for the stones involved and the islands they are in. A resting
// stone within an island member's reach over the pass does not join: it is the island's fixed
// obstacle (kept out of, never moved) and wakes only when the island's solve acts on it; the
// island then stops at the lattice point before that sub-step and is formed anew there with it
// (the pass ends there, as where a member leaves). Members leave
// the island as the single-stone fallback's stone does (flight, plane contact, rest); an island
// that rests, rests whole. Not exact yet: a flight that begins inside a step (a lift-off, a
// separation from an island) is searched against other stones from the end of that step; a command
// (set_state, remove) on an island member dissolves its island into single-stone fallbacks (they
// rejoin at once if they touch). Stones far from each other cost as before.
//
// Stones live in a table (world/stone_table.h): each has a StoneId given once and never again,
// refers to a body (world/world_body.h: its motion model and lens; one body per colour, or the
// config's body), and is addressed either by id or by index (0 .. stone_count()-1, the order of
// the ids; indices shift when a stone is removed, ids never change). Stones are added, removed
// and cleared while the world runs; a removed stone costs nothing afterwards.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "virtual_go/contact/pair_gap_bound.h"
#include "virtual_go/contact/pair_time_of_impact.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/world/broad_phase.h"
#include "virtual_go/world/flight_track.h"
#include "virtual_go/world/nonsmooth_contact.h"
#include "virtual_go/world/nonsmooth_island.h"
#include "virtual_go/world/stone_id.h"
#include "virtual_go/world/stone_mode.h"
#include "virtual_go/world/stone_table.h"
#include "virtual_go/world/world_body.h"
#include "virtual_go/world/world_config.h"
#include "virtual_go/world/world_counters.h"
#include "virtual_go/world/world_event.h"

namespace virtual_go {

// A bound on the work of one World::advance_to call, in the units of WorldCounters::work():
// time-of-impact searches and their steps, impacts and their slip steps, plane-contact
// integrator steps and fallback sub-steps, summed over all stones.
struct WorkBudget {
  long max_steps = std::numeric_limits<long>::max();  // > 0
};

// How far a budgeted advance_to got.
struct AdvanceResult {
  bool reached = true;  // time() == the requested time
  double time_s = 0.0;  // time() after the call: every stone is there
  long work = 0;        // WorldCounters::work() spent by the call
};

class World {
 public:
  // One stone, or several, at t0_s (world time line, s), each of the config's body (body 0) with
  // ids 0, 1, ... in the order given. Throws InvalidArgument naming the field
  // for a bad configuration, a bad state ("state", "stone 2: ...") or a stone overlapping the
  // board or the table by more than the touch tolerance. Events at t0 (a stone placed resting on
  // the board comes to rest at once) are reported by the first advance_to.
  World(const WorldConfig& config, const RigidBodyState& initial_state, double t0_s);
  World(const WorldConfig& config, const std::vector<RigidBodyState>& initial_states, double t0_s);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Starts over with these stones (of the config's body) at t0_s; counters are zeroed. Same
  // checks as the constructor; on error nothing changes. The stones get new ids (ids are never
  // given twice in one world); bodies added so far are kept.
  void reset(const std::vector<RigidBodyState>& states, double t0_s);

  // Advances every stone to t_s (>= time()) through all events, appending them in time order
  // (ties: by stone, then in the order they happened). Throws InvalidArgument for a non-finite t_s
  // or one before time(), nothing changed. A plane contact that fails (no consistent contact
  // force, an integrator failure) hands the stone to the fallback; IntegrationError escapes
  // only if an impact's slip integration fails.
  void advance_to(double t_s, std::vector<WorldEvent>& events);

  // The same with a work budget, so that a caller with a deadline (the node's timer) can bound
  // the work per call. When the budget is spent before t_s, every stone is stopped at one time
  // t_stop in [time(), t_s] (time() becomes t_stop; states exact there as ever: no overlap, no
  // energy gain, events up to t_stop appended) and the result says reached = false; the next
  // call goes on from there. Bound: the work of one call is at most 2 * max_steps plus one
  // indivisible unit per stone in contact: an impact (ImpactOptions::max_steps slip steps at most),
  // a time-of-impact search (TimeOfImpactOptions::max_steps), a plane-contact step with its event
  // location, or a fallback sub-step. (The factor 2: when several stones are in contact, the
  // budget is shared among them, and those that went past the stop time of another are taken
  // back and advanced to it again, which costs at most what they had spent.) A budget is split
  // evenly among the stones in contact; each gets at least one step, so every call makes progress
  // unless a stone is at an instant with several transitions. Stone contact: a spent budget ends
  // the call between pipeline passes, but the first pass of a call always steps (so a pass whose
  // pair search alone costs more than the budget still makes progress); the pair searches of a
  // pass share what is left (each at least one step, one indivisible full search when its share
  // made no progress), and each island gets at least one sub-step and stops the pass where the
  // budget stops it. So the bound grows by one pass's pair work (one unit per candidate pair)
  // and one sub-step per island. Throws InvalidArgument for max_steps < 1 besides the checks above.
  AdvanceResult advance_to(double t_s, std::vector<WorldEvent>& events, const WorkBudget& budget);

  // A command: the stone's state becomes `state` at t_s (>= time(); the world is first advanced
  // to t_s, its events appended). A resting stone is woken (a `wake` event first); events the
  // new state has at t_s itself (an impact, a contact start, rest) follow. Throws
  // InvalidArgument for an unknown stone, a bad state or one overlapping the board, before
  // anything changes.
  void set_state(std::size_t stone, const RigidBodyState& state, double t_s,
                 std::vector<WorldEvent>& events);

  // ---- Bodies. Body 0 is the config's (motion, shape); others are added. A body is never
  // removed (stones refer to it by its index).
  // Adds a body (the world's gravity and board apply). Throws InvalidArgument ("body/inertia",
  // "gravity") before anything changes.
  std::size_t add_body(const WorldBody& body);
  // The body of a colour: the default StoneSet's (black slate 22.2 mm, white shell 21.9 mm, size
  // 33) with the config's motion-model kind, made at its first use and shared by every stone of
  // that colour afterwards. Throws InvalidArgument ("color") for a value outside the enum.
  std::size_t color_body(StoneColor color);
  std::size_t body_count() const { return bodies_.size(); }
  const WorldBodyModel& body_model(std::size_t body) const;  // std::out_of_range if unknown

  // ---- Stones by id.
  // Adds a stone of `body` (or of the colour's body) with `state` at t_s (>= time(); the world is
  // first advanced to t_s, its events appended). Events the new stone has at t_s itself follow
  // (a stone set down resting on the board rests at once: its `rest` event). Throws
  // InvalidArgument before anything changes: "body" (unknown), "color", "time", "state" (not
  // finite, zero quaternion, or overlapping the board or the table).
  StoneId add_stone(std::size_t body, const RigidBodyState& state, double t_s,
                    std::vector<WorldEvent>& events);
  StoneId add_stone(StoneColor color, const RigidBodyState& state, double t_s,
                    std::vector<WorldEvent>& events);
  // Advances to t_s, then removes the stone (no event: the caller asked). Throws
  // InvalidArgument ("stone" for an unknown or removed id, "time") before anything changes.
  void remove_stone(StoneId id, double t_s, std::vector<WorldEvent>& events);
  // Removes every stone; time() becomes t_s (>= time(), else InvalidArgument "time"). Bodies,
  // counters and the id sequence are kept.
  void clear(double t_s);
  // set_state by id.
  void set_state(StoneId id, const RigidBodyState& state, double t_s,
                 std::vector<WorldEvent>& events);
  // Moves a resting stone lying on the board's top face horizontally to (x, y) without waking
  // it: it stays resting, its orientation and height unchanged, its velocities zero (the
  // placement's nudge, world/stone_placement.h). Advances to t_s first, then appends a `rest`
  // event (detail nudge) with the new pose, so a recording sees it. Throws InvalidArgument
  // before anything changes: "stone" (unknown, or not resting), "position" (not finite, or its
  // lowest point would leave the top face), "time".
  void move_resting_stone(StoneId id, const Eigen::Vector2d& position_xy_world, double t_s,
                          std::vector<WorldEvent>& events);

  bool contains(StoneId id) const { return stones_.index_of(id).has_value(); }
  // The index of a live stone; InvalidArgument ("stone") naming the id otherwise.
  std::size_t index_of(StoneId id) const;
  StoneId id(std::size_t stone) const;  // std::out_of_range if no such index
  // The live stones' ids in index order: `for (StoneId id : world.stone_ids())`.
  const std::vector<StoneId>& stone_ids() const { return stones_.ids(); }
  const RigidBodyState& state(StoneId id) const { return state(index_of(id)); }
  StoneMode mode(StoneId id) const { return mode(index_of(id)); }
  bool is_resting(StoneId id) const { return is_resting(index_of(id)); }
  std::size_t body_of(StoneId id) const { return body_of(index_of(id)); }
  std::optional<StoneColor> color(StoneId id) const;
  double energy(StoneId id) const { return energy(index_of(id)); }

  // ---- Stones by index (std::out_of_range for an index >= stone_count()).
  double time() const { return time_; }
  std::size_t stone_count() const { return stones_.size(); }
  const RigidBodyState& state(std::size_t stone) const;  // at time()
  StoneMode mode(std::size_t stone) const;
  bool is_resting(std::size_t stone) const { return mode(stone) == StoneMode::resting; }
  bool all_resting() const { return stones_.all_resting(); }
  ContactPhase contact_phase(std::size_t stone) const;  // derived from mode()
  std::size_t body_of(std::size_t stone) const;
  // In flight: the time of the flight's first contact once found, +infinity while none is known.
  double next_contact_time(std::size_t stone) const;
  // Total energy (J) under the stone's own body: 1/2 m v^2 + 1/2 omega . L - m g . x_G
  // (body_energy).
  double energy(std::size_t stone) const;

  const WorldConfig& config() const { return config_; }
  // The config's body (body 0): the single-stone node's stone.
  const MotionSetup& setup() const { return bodies_[0].setup(); }
  const LensGeometry& lens() const { return bodies_[0].lens(); }
  const BoardDistance& board_distance() const { return bodies_[0].board(); }
  const WorldCounters& counters() const { return counters_; }
  // The box (world, m) the pair search trusts a stone to stay within over the next dt_s (>= 0;
  // stage 1a): its rim sphere about every place its centre can reach while its energy (its
  // island's) does not rise, widened by the jump of a stone the fallback or an island moves.
  // Throws InvalidArgument ("stone" unknown, "dt" negative or not finite). For tests.
  Bounds reach_bounds_of(StoneId id, double dt_s) const;

 private:
  void check_state(const std::string& field, const WorldBodyModel& body,
                   const RigidBodyState& state) const;
  void check_time(const std::string& what, double t_s) const;
  void check_stone_index(std::size_t stone) const;
  const WorldBodyModel& body_at(std::size_t i) const { return bodies_[stones_.body(i)]; }
  // A new row of `body` in flight from `state` at t_s, its events at t_s processed.
  std::size_t start_stone(std::size_t body, const RigidBodyState& state, double t_s);
  void start_stones(const std::vector<RigidBodyState>& states, double t0_s);
  // True when the stone reached t_s (or rests); false when the work counter hit work_limit
  // first (the stone is then at hot_[i].state_time_s < t_s).
  bool advance_stone(std::size_t i, double t_s, long work_limit);
  bool is_cheap(std::size_t i, double t_s) const;
  void sample_flight(std::size_t i, double t_s);
  bool advance_flight(std::size_t i, double t_s);
  bool advance_plane(std::size_t i, double t_s, long work_limit);
  bool advance_nonsmooth(std::size_t i, double t_s, long work_limit);
  TimeOfImpact search(std::size_t i, double from_s, double to_s);
  void begin_flight(std::size_t i, const RigidBodyState& state, double t_s, bool after_lift_off);
  void handle_contact(std::size_t i);
  void enter_sustained(std::size_t i, const RigidBodyState& state, double t_s,
                       const BoardContact& contact);
  void start_nonsmooth(std::size_t i, const RigidBodyState& state, double t_s,
                       WorldEventDetail detail, const BoardContact* contact);
  void come_to_rest(std::size_t i, const RigidBodyState& state, double t_s,
                    WorldEventDetail detail);
  bool transition_allowed(std::size_t i, double t_s);
  void sync_plane_counters(std::size_t i);
  void sync_nonsmooth_counters(std::size_t i);
  // Adds a fallback's or an island's work since `seen` to the world's counters; seen = now.
  void add_nonsmooth_work(const NonsmoothCounters& now, NonsmoothCounters& seen);
  WorldEvent& emit(std::size_t i, double t_s, WorldEventKind kind, WorldEventDetail detail,
                   const RigidBodyState& state);
  const ContactMaterial& material_of(const BoardFeature& feature) const;
  void flush(std::vector<WorldEvent>& events);

  // ---- Stone-stone contact (world_pairs.cpp): the pipeline's stages 1, 2 and 4.
  // What stage 2 found: the time the pass steps to and what happens there.
  struct Interaction {
    enum class Kind { none, impact, join };
    double time_s = 0.0;
    Kind kind = Kind::none;
    std::size_t a = 0, b = 0;  // stone indices (impact, join)
    PairTimeOfImpact hit;      // impact
  };
  // One island of touching stones: its members by id (member k of the island), which are still
  // in it, and the island's counters already added to the world's.
  struct IslandRun {
    std::size_t key = 0;
    NonsmoothIsland island;
    std::vector<StoneId> members;
    std::vector<char> in;
    NonsmoothCounters seen;
    std::vector<StoneId> obstacles;  // the resting stones it keeps out of (next_interaction)
    std::vector<std::size_t> woken;  // stone indices its last advance woke (advance_islands)
  };
  // Stage 3: every awake stone to t_s by its own model (the per-stone advance with the work
  // limit); false when the budget stopped it first (time() is then the stop time).
  bool step_stones(double t_s, long work_limit, bool bounded);
  // Stages 1 and 2: the earliest interaction up to t_s (or t_s). With a work limit, the pair
  // searches share what is left of it (each at least one step, an exhausted search ends the pass
  // where it got to).
  Interaction next_interaction(double t_s, long work_limit);
  void resolve_interaction(const Interaction& next);
  void collide_pair(std::size_t a, std::size_t b, const PairTimeOfImpact& hit);
  // Stones a and b (and the islands they are in) become one island at t_s from `states` (or
  // their present states).
  void form_island(const std::vector<std::size_t>& seeds, const std::vector<RigidBodyState>& states,
                   double t_s);
  // Every island to t_s, each stopping where members leave it; t_s becomes the earliest such
  // time. (With several islands, one advanced before another stopped earlier stays ahead of
  // time() by less than a pass; its next advance waits for the world.)
  // Each island gets at least one sub-step; one that stops at the work limit ends the pass there.
  void advance_islands(double& t_s, long work_limit);
  // To t_s, the first lattice time where members leave, where a sub-step acted on an obstacle
  // (run.woken: the island is formed anew there with it), or where the work limit stopped it
  // (returned); members that leave are left there.
  double advance_island(IslandRun& run, double t_s, long work_limit);
  // Each member but `except` goes on in its own single-stone fallback.
  void dissolve_island(std::size_t key, std::size_t except);
  IslandRun* island_of(std::size_t i);
  const IslandRun* island_of(std::size_t i) const;
  StoneMotion stone_motion(std::size_t i) const;
  // A bound (m/s) on the speed of every point of the stone over the next dt_s while its energy
  // (its island's) does not rise: kinetic energy at most the energy above the lowest potential
  // (the lens lying flat on the table, or on the top face when it cannot leave it in dt_s).
  double point_speed_bound(std::size_t i, double dt_s) const;
  // The kinetic energy bound of that rule for stone i alone (J); memoised within a pair search.
  double kinetic_energy_bound(std::size_t i, double dt_s) const;
  double kinetic_energy_bound_now(std::size_t i, double dt_s) const;
  // The potential energy (J) stone i cannot go below within dt_s (its floor: the top face or the
  // table, kinetic_energy_bound_now).
  double lowest_potential(std::size_t i, double dt_s) const;
  // That bound for stone i, or the sum over its island's members when it is in one (J).
  double shared_kinetic_energy_bound(std::size_t i, double dt_s) const;
  // Bounds (world, m) that awake stone i cannot leave over the next dt_s while its energy (its
  // island's) does not rise: its rim sphere about every place its centre can reach.
  Bounds reach_bounds(std::size_t i, double dt_s) const;
  // Bounds of stone i's motion over the pass for the second-order gap bound
  // (contact/pair_gap_bound.h): resting, flying, or in plane contact on the top face with a
  // cap (then its force bound); nothing for an island member or the fallback.
  std::optional<GapBoundMotion> gap_bound_motion(std::size_t i, double dt_s);
  // How long the gap of the pair (i, j), c = lens_pair_distance(i, j), stays above half the
  // join margin by the second-order bound; 0 when it does not apply.
  // level_m: the gap it must stay above (default: half the join margin).
  double second_order_step(std::size_t i, std::size_t j, const LensPairContact& c, double dt_s,
                           double level_m);
  // How far a point of stone i may jump within a pass beyond its speed bound times the pass's
  // length (m): 0 but for a stone an island or the fallback moves (its samples between lattice
  // points are partial sub-steps with position corrections, or the next lattice state itself).
  double jump_bound(std::size_t i) const;
  // The broad phase holds every resting stone (its rim sphere, entered when it comes to rest)
  // and every awake stone (its bounds for the pass, entered by the pair search).
  void enter_fallen_asleep();
  void rebuild_broad_phase();

  WorldConfig config_;
  std::vector<WorldBodyModel> bodies_;  // [0]: the config's
  std::optional<std::size_t> color_bodies_[2];
  double time_ = 0.0;
  StoneTable stones_;  // only its awake stones are visited by advance_to
  std::vector<WorldEvent> pending_;
  WorldCounters counters_;
  std::vector<std::unique_ptr<IslandRun>> islands_;
  std::size_t next_island_key_ = 0;
  BroadPhase broad_phase_{1.0, 1.0};  // cells: the board's spacing (set by the constructor)
  std::vector<double> flight_end_;    // per stone, scratch of the pair search (awake ones only)
  // Per stone, scratch of the pair search: an awake stone whose bounds for the whole call meet
  // no other stone's (next_interaction, stage 1).
  std::vector<char> alone_;
  // kinetic_energy_bound's answers within one pair search (next_interaction: no stone's state
  // changes between its first bound and its end), per stone for the two spans it asks (the
  // pass's and the jump's): an island's shared bound sums its members' for each member.
  struct KineticBoundMemo {
    long search = -1;  // bound_search_ when written
    double dt_s = 0.0, kinetic_j = 0.0;
  };
  mutable std::vector<KineticBoundMemo> kinetic_memo_;  // 2 per stone
  long bound_search_ = 0;  // counts pair searches; 0 outside one (no memo)
  long bound_searches_ = 0;
};

}  // namespace virtual_go
