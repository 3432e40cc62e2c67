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
// Stones do not interact yet (stone-stone contact is later work): each one's events are found on
// its own, then merged in time order.
//
// Per-stone data is kept in two arrays (as in Box2D v3's solver sets): the hot part every call
// reads (state, mode, the times up to which a flight needs only sampling) and the bookkeeping
// touched at events (the flight's anchor and cache, the contact phase).
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/world/flight_track.h"
#include "virtual_go/world/nonsmooth_contact.h"
#include "virtual_go/world/stone_mode.h"
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
  // One stone, or several, at t0_s (world time line, s). Throws InvalidArgument naming the field
  // for a bad configuration, a bad state ("state", "stone 2: ...") or a stone overlapping the
  // board or the table by more than the touch tolerance. Events at t0 (a stone placed resting on
  // the board comes to rest at once) are reported by the first advance_to.
  World(const WorldConfig& config, const RigidBodyState& initial_state, double t0_s);
  World(const WorldConfig& config, const std::vector<RigidBodyState>& initial_states, double t0_s);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Starts over with these stones at t0_s; counters are zeroed. Same checks as the constructor;
  // on error nothing changes.
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
  // unless a stone is at an instant with several transitions. Throws InvalidArgument for
  // max_steps < 1 besides the checks above.
  AdvanceResult advance_to(double t_s, std::vector<WorldEvent>& events, const WorkBudget& budget);

  // A command: the stone's state becomes `state` at t_s (>= time(); the world is first advanced
  // to t_s, its events appended). A resting stone is woken (a `wake` event first); events the
  // new state has at t_s itself (an impact, a contact start, rest) follow. Throws
  // InvalidArgument for an unknown stone, a bad state or one overlapping the board, before
  // anything changes.
  void set_state(std::size_t stone, const RigidBodyState& state, double t_s,
                 std::vector<WorldEvent>& events);

  double time() const { return time_; }
  std::size_t stone_count() const { return hot_.size(); }
  const RigidBodyState& state(std::size_t stone) const;  // at time()
  StoneMode mode(std::size_t stone) const;
  bool is_resting(std::size_t stone) const { return mode(stone) == StoneMode::resting; }
  bool all_resting() const { return awake_.empty(); }
  ContactPhase contact_phase(std::size_t stone) const;
  // In flight: the time of the flight's first contact once found, +infinity while none is known.
  double next_contact_time(std::size_t stone) const;
  // Total energy (J): 1/2 m v^2 + 1/2 omega . L - m g . x_G.
  double energy(std::size_t stone) const;

  const WorldConfig& config() const { return config_; }
  const MotionSetup& setup() const { return config_.motion; }
  const LensGeometry& lens() const { return lens_; }
  const BoardDistance& board_distance() const { return board_; }
  const WorldCounters& counters() const { return counters_; }

 private:
  // Read on every call.
  struct StoneHot {
    RigidBodyState state;
    double state_time_s = 0.0;
    StoneMode mode = StoneMode::flight;
    // Flight: sampling alone suffices for t < next_contact_s and t <= clear_until_s.
    double next_contact_s = std::numeric_limits<double>::infinity();
    double clear_until_s = std::numeric_limits<double>::infinity();
  };
  // Touched at events.
  struct StoneRecord {
    FlightTrack flight;
    ContactPhase phase = ContactPhase::none;
    std::optional<PlaneContact> plane;
    std::optional<NonsmoothContact> nonsmooth;
    PlaneContactCounters plane_seen;  // the phase's counters already added to the world's
    NonsmoothCounters nonsmooth_seen;
    double transition_time_s = -std::numeric_limits<double>::infinity();
    int transitions_at_instant = 0;
  };

  void check_state(const std::string& field, const RigidBodyState& state) const;
  // Sets the stone's mode and keeps awake_ in step with it: every mode change goes through here
  // (or through sync_awake after a state is restored wholesale).
  void set_mode(std::size_t i, StoneMode mode);
  void sync_awake(std::size_t i);
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
  WorldEvent& emit(std::size_t i, double t_s, WorldEventKind kind, WorldEventDetail detail,
                   const RigidBodyState& state);
  const ContactMaterial& material_of(const BoardFeature& feature) const;
  void flush(std::vector<WorldEvent>& events);

  WorldConfig config_;
  LensGeometry lens_;
  BoardDistance board_;
  std::unique_ptr<Integrator> exact_;
  double time_ = 0.0;
  std::vector<StoneHot> hot_;
  std::vector<StoneRecord> records_;
  // The stones not resting, in no particular order (removal swaps with the last), and each
  // stone's slot in it (kAsleep while it rests). Only these are visited by advance_to.
  static constexpr std::size_t kAsleep = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> awake_;
  std::vector<std::size_t> awake_slot_;
  std::vector<WorldEvent> pending_;
  WorldCounters counters_;
};

}  // namespace virtual_go
