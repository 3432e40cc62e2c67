// The stone node without ROS: a checked configuration -> core objects, a simulated clock on a
// fixed grid of whole nanoseconds, and the changes requested from outside. The node calls
// update() with ROS time on every timer tick (with ~publish_clock, with the simulated times
// sim/sim_pacer picks) and publishes what it returns.
//
// With ~board/enabled the stone lives in a World (world/world.h): every grid time is a
// World::advance_to, each World event becomes a segment event with the exact state at its
// instant (stamp = the instant rounded down to a whole ns, plus time_offset_s), and commands are
// World state replacements (a resting stone wakes). The World's time line is seconds since
// epoch_ns() (the start, or the last time jump): absolute ROS times as doubles (~1.7e9 s) would
// resolve only 2e-7 s. A resting stone costs nothing: the World is not called while it rests
// and no change is due, and its state and outputs stay bit for bit.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/go/stone_color.h"
#include "virtual_go/sim/segment_event.h"
#include "virtual_go/sim/sim_clock.h"
#include "virtual_go/sim/state_output.h"
#include "virtual_go/sim/state_request.h"
#include "virtual_go/sim/stone_config.h"
#include "virtual_go/sim/update_budget.h"
#include "virtual_go/world/stone_placement.h"
#include "virtual_go/world/world.h"

namespace virtual_go {

struct UpdateResult {
  bool advanced = false;             // a new state exists at stamp_ns: publish it
  std::int64_t stamp_ns = 0;         // simulated time of state()
  std::vector<SegmentEvent> events;  // new segments started during this update, in order
  // Set once, by the update at which a step failed (log it): its cause. The state is then
  // held and nothing is published until reset, set_state or an auto reset replaces it.
  std::string error;
  // Physics steps due at ROS time that the work budget left for the next update (0: none), and
  // how far simulated time then trails the ROS time asked for (ns). Past the clock's maximum
  // lag (1 s) the simulation skips ahead with a time_jump event instead of catching up.
  std::int64_t steps_deferred = 0;
  std::int64_t behind_ns = 0;
};

// Most ticks one ~step may queue (with those already queued): 1000 s of simulation at the
// default ~dt; a larger number is a typo more likely than a wish.
constexpr std::int64_t kMaxStepTicks = 1000000;

// A request refused for a reason other than a bad field: the state is held after a failed
// step, or too many requests wait for a step. what() says why and what to do.
class RequestRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Highest ~place drop (m from the board's top face to the stone's lowest point): a stone dropped
// from 2 m hits the board at 6.3 m/s, beyond any player's hand; higher is a unit mistake.
constexpr double kMaxDropHeightM = 2.0;

// A ~place request (with the board). Either a Go point (then the position comes from it and
// drop_height_m, lying flat; twist as given) or, with point empty, a full pose.
struct PlaceRequest {
  std::string point;  // "A1" ... "T19", or "" to use the pose
  std::string color;  // "black" | "white"
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
  Eigen::Vector4d orientation_xyzw = Eigen::Vector4d::Zero();  // all zeros: lying flat
  double drop_height_m = 0.0;  // point only: 0 = set down at rest (nudging neighbours)
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_world = Eigen::Vector3d::Zero();
};

// A stone added by ~place: its name (also its tf frame), colour and World identity.
struct PlacedStone {
  std::string name;
  StoneColor color = StoneColor::black;
  StoneId id;
};

class StoneSimulation {
 public:
  // Throws ConfigError naming the parameter.
  explicit StoneSimulation(const StoneConfig& config);
  // A configuration from check_config() (tests may alter it to reach states the checks refuse).
  explicit StoneSimulation(CheckedConfig checked);

  // Advances to the latest grid time at or before ROS time now_ns (0 = not valid yet). Never
  // throws: whatever fails holds the state, and is reported once in UpdateResult::error and
  // to the next request. `budget` is asked before every step after the first: once it is
  // spent the update returns, and the steps left come at the next update (a slow scene makes
  // the simulation trail ROS time; the caller stays responsive). Without one, every step due.
  UpdateResult update(std::int64_t now_ns, UpdateBudget& budget) noexcept;
  UpdateResult update(std::int64_t now_ns) noexcept;

  // Requests validate at once (InvalidArgument naming the field and its limit; nothing
  // changes) and take effect at the next grid time, which becomes the first state of a new
  // segment: stamps stay strictly increasing and the state already published at the current
  // time stays true. Requests due at the same step apply in order, each announced by its own
  // event with the state it makes (segments of zero length but the last). At most
  // kMaxPendingRequests wait; more are refused (RequestRefused). Each returns the answer for
  // the caller: "applied at the next physics step", plus the cause of a failed step not yet
  // reported. A step that fails is announced by a `held` event (detail: the cause) and its
  // requests are not applied; the next request's answer names it.
  std::string reset();
  // `name`: the stone addressed, "" or stone_name(0) for the initial stone, else a name ~place
  // answered (also one still waiting to be placed). InvalidArgument ("name") for a name no
  // stone has, or one removed (also by a ~remove or ~clear waiting for the step): the message
  // quotes it and lists the stones there are; nothing changes.
  // frame: "" / "world" / world frame id, or "stone" / the stone's frame id (its name) for its
  // body frame. For rigid_body this sets L = I w at the instant it takes effect. Refused
  // (RequestRefused) while the state is held: it would change a state that cannot move.
  std::string set_angular_velocity(const Eigen::Vector3d& omega, const std::string& frame,
                                   const std::string& name = "");
  // Limits as for the initial stone; a placed stone's state is checked with its own body (its
  // colour's lens against the board).
  std::string set_state(const Eigen::Vector3d& position_world,
                        const Eigen::Vector4d& orientation_xyzw,
                        const Eigen::Vector3d& velocity_world,
                        const Eigen::Vector3d& angular_velocity_world,
                        const std::string& name = "");

  // Stones on the board (~board/enabled only; without it RequestRefused). The initial stone,
  // `stone_name(0)`, is the one the requests above address; ~place adds stones named
  // "<color>_<n>" (n = 1, 2, ... per colour, never reused, also after a remove or clear), the name
  // reserved and returned at once; the stone appears at the next physics step, as every request.
  // Errors (InvalidArgument naming the field: "point", "color", "drop_height" (0 ..
  // kMaxDropHeightM), "pose.position", "pose.orientation", "twist.linear", "twist.angular") change
  // nothing. A placement the World refuses when it applies (no room to set down without pushing a
  // stone off the board) adds nothing; the next request's answer says so.
  // Returns the new name; `answer` gets the answer for the caller.
  std::string place(const PlaceRequest& request, std::string& answer);
  // A name ~place answered, or a Go point: the stone whose nearest point it is (one waiting to be
  // placed there first, else the one nearest that intersection). The initial stone is removed
  // like any other (a game replayed onto the board must not have a stone the game lacks);
  // ~reset puts it back at its initial state. InvalidArgument ("name") for an unknown or removed
  // name or an empty point. Returns the removed stone's name; `answer` as above.
  std::string remove(const std::string& name_or_point, std::string& answer);
  // The stone at a Go point, as remove() finds it: one waiting to be placed there (the latest),
  // else the stone nearest the intersection among those whose nearest point it is and that are
  // still there once the waiting requests apply (the initial stone too); "" when there is none
  // (or no board).
  std::string stone_at(GoPoint point) const;
  // Removes every stone, the initial one too, at the next step (a clear event each).
  std::string clear();
  // The initial stone is in the simulation (not removed by ~remove or ~clear since the last
  // ~reset; always without the board). While it is not, state() and output() keep its last
  // state, nothing of it is published, and it never rests or auto-resets.
  bool initial_present() const { return !initial_removed_; }
  // The placed stones in the World now, in placement order.
  const std::vector<PlacedStone>& placed_stones() const { return placed_; }

  // Simulation controls. While paused no step is taken however ROS time moves (the state, its
  // stamp and the clock stay as last published; requests queue as ever), except the ticks
  // step() queues. Without ~publish_clock simulated time follows ROS time, so the first update
  // after unpause() skips the paused interval: a time_jump event (detail "unpaused") at the ROS
  // time, the state continuing from where it stood (no jump when ROS time has not moved on by a
  // step). With ~publish_clock the simulation owns the time and simply goes on. Each returns
  // the answer for the caller; pause and unpause are idempotent.
  std::string pause();
  std::string unpause();
  // Queues `ticks` steps of dt, taken by the next updates (as their budgets allow) whatever ROS
  // time says. InvalidArgument ("ticks") for 0 or more than kMaxStepTicks queued; RequestRefused
  // while not paused.
  std::string step(std::int64_t ticks);
  bool paused() const { return paused_; }
  std::int64_t steps_queued() const { return steps_queued_; }

  const StoneConfig& config() const { return checked_.config; }
  const Stone& stone() const { return checked_.stone; }
  const MotionSetup& setup() const { return checked_.setup; }
  const Integrator& integrator() const { return *integrator_; }
  std::int64_t dt_ns() const { return checked_.dt_ns; }
  // s, as the integrator sees it: from the whole nanoseconds, not the ~dt parameter.
  double dt_s() const { return checked_.dt_s; }
  const RigidBodyState& initial_state() const { return checked_.initial_state; }
  // With ~board/enabled the checked world (board, table, materials); otherwise nothing.
  const std::optional<WorldConfig>& world_config() const { return checked_.world; }
  // Simulated time of the initial state (the first valid ROS time seen); 0 before.
  std::int64_t start_ns() const { return start_ns_; }
  bool started() const { return clock_.started(); }
  const RigidBodyState& state() const { return state_; }
  RigidBody body() const { return RigidBody(checked_.setup.model, state_); }
  // What messages show of state() (after an update that advanced): checked finite.
  const StateOutput& output() const { return output_; }
  std::int64_t time_ns() const { return clock_.time_ns(); }
  // How far simulated time may trail ROS time before it skips ahead (a time_jump event).
  std::int64_t max_lag_ns() const { return clock_.max_lag_ns(); }
  // True after a failed step until a change replaces the state.
  bool held() const { return held_; }
  // While held(): the cause of the failed step.
  const std::string& failure() const { return failure_; }
  // With the board: the World holds the stone at rest (without the board it never rests).
  bool resting() const { return world_ && !initial_removed_ && world_->is_resting(initial_id_); }
  // With the board: the World (its counters show the work done), else nullptr.
  const World* world() const { return world_ ? &*world_ : nullptr; }
  // Simulated time (ns) of the World's time 0.
  std::int64_t epoch_ns() const { return epoch_ns_; }
  std::size_t pending_requests() const { return pending_.size(); }
  // The name of the World's stone `index` (events and ~stones carry it), also its tf frame:
  // today the single stone, index 0, named by ~stone_frame.
  const std::string& stone_name(std::size_t index) const;

 private:
  struct Change {
    EventReason reason;
    RigidBodyState state;  // reset, set_state: the new state; place by pose: the stone's
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();  // set_angular_velocity
    RequestFrame frame = RequestFrame::world;
    // place, remove: the stone's name; place: colour, point (absent: `state`), drop height.
    std::string name;
    StoneColor color = StoneColor::black;
    std::optional<GoPoint> point;
    double drop_height_m = 0.0;
    Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_velocity_world = Eigen::Vector3d::Zero();
    bool on_board() const {
      return reason == EventReason::place || reason == EventReason::remove ||
             reason == EventReason::clear;
    }
    // set_state, set_angular_velocity: `name` empty for the initial stone, else a placed one's.
    bool initial_stone() const { return !on_board() && name.empty(); }
    bool replaces_state() const {
      return reason != EventReason::set_angular_velocity && initial_stone();
    }
    // place at a point: set down at rest (no drop height, no twist), its room planned.
    bool sets_down() const {
      return point && drop_height_m == 0.0 && velocity_world.isZero(0.0) &&
             angular_velocity_world.isZero(0.0);
    }
    // set_angular_velocity: `omega` in the world frame, for a stone in state `now`.
    Eigen::Vector3d omega_world(const RigidBodyState& now) const;
  };
  // Names and bodies (src/sim/stone_simulation.cpp).
  // The name of the stone with this World id ("" if none).
  std::string name_of(StoneId id) const;
  // The motion model of a World stone's body, for its outputs.
  const MotionModel& model_of(StoneId id) const;
  // The placed stone of that name, or nullptr.
  const PlacedStone* placed_named(const std::string& name) const;
  // The ~place waiting for the next step that gives that name, or nullptr.
  const Change* place_waiting(const std::string& name) const;
  // The initial stone's name (also while it is removed), a placed stone's or one a waiting
  // ~place gives; a removed placed stone's name is none of these (names are never reused).
  bool names_a_stone(const std::string& name) const {
    return name == stone_name(0) || placed_named(name) || place_waiting(name);
  }

  // Requests, checked and queued (stone_simulation_requests.cpp).
  void require_board(const std::string& request) const;
  // The name a request addresses: "" for the initial stone, or a placed stone's (one waiting to
  // be placed too), as the board will be after the requests waiting. Throws InvalidArgument
  // ("name") quoting an unknown or removed one and listing the stones there are.
  std::string request_target(const std::string& name) const;
  // The names there will be once the pending requests apply, in ~stones order.
  std::vector<std::string> names_after_pending() const;
  // Refuses (InvalidArgument naming `field`) a state overlapping the board or the table.
  // (Of the initial stone's body, or of `board`'s.)
  void check_clear_of_board(const std::string& field, const RigidBodyState& state,
                            const BoardDistance* board = nullptr) const;
  void enqueue(Change change);
  std::string answer();

  // The planned layout, for the room check (stone_simulation_planning.cpp).
  // Throws InvalidArgument ("point") when a stone of `body` set down at `point` will find no room
  // on the board as the pending requests leave it (stones that move in that step aside); else
  // returns the plan, for planned_after().
  SetDownPlan check_room(std::size_t body, GoPoint point);
  // The planner's layout as the pending requests leave it, each request planned once: rebuilt
  // from the World only when the World or the queue changed under it (planned_.valid false).
  const std::vector<PlanStone>& planned_layout();
  // The change just queued (the last of pending_), set down by `plan` (check_room's), applied
  // to the planned layout without planning it again.
  void planned_after(const SetDownPlan& plan);
  // One pending request applied to the planned layout, as it will apply to the World.
  void plan_change(const Change& c);

  // The time line (stone_simulation_timeline.cpp).
  void advance_to(std::int64_t now_ns, UpdateBudget& budget, UpdateResult& result);
  // Takes up to `steps` steps (the first always, the others while the budget lasts); returns how
  // many it took.
  std::int64_t take_steps(std::int64_t steps, UpdateBudget& budget, UpdateResult& result);
  // The time line restarts at now_ns (a time jump, or the end of a pause): a new segment.
  void jump_to(std::int64_t now_ns, const std::string& detail, UpdateResult& result);
  void hold(const std::string& cause, UpdateResult& result);

  // One physics step (stone_simulation_step.cpp).
  // False: the step is not finished (the World is part-way to the next grid time, the budget
  // spent); the next update continues it.
  bool step(UpdateResult& result, UpdateBudget& budget);
  bool step_world(UpdateResult& result, UpdateBudget& budget);
  // A change applied at a step: its reason and the state it makes (output: filled by step()).
  struct Applied {
    EventReason reason;
    RigidBodyState state;
    StateOutput output;
  };
  // The initial stone's changes among pending_[0, end).
  std::vector<Applied> apply_changes(bool auto_reset, RigidBodyState& next,
                                     std::size_t end = static_cast<std::size_t>(-1)) const;
  bool auto_reset_due(std::int64_t next_ns) const;
  // A change due at the next step replaces the state (reset, set_state, auto reset).
  bool replacement_due() const;
  // A ~remove of the initial stone or a ~clear.
  bool removes_initial(const Change& change) const {
    return change.reason == EventReason::clear ||
           (change.reason == EventReason::remove && change.name == stone_name(0));
  }
  // The state was replaced from outside the integration: a new segment's first state.
  void replace_state(const RigidBodyState& state);

  // The World kept in step (stone_simulation_world.cpp).
  // With the board: the World restarted with state_ at stamp_ns (its new epoch), and its events
  // at that instant (a stone placed on the board comes to rest) reported.
  void restart_world(std::int64_t stamp_ns, UpdateResult& result);
  // The World restarted at t_s with the initial stone in `state` and every placed stone where it
  // is (they get new ids).
  void reset_world(const RigidBodyState& state, double t_s);
  // ~place / ~remove / ~clear changes due at this step applied to the World at t_s, in order, with
  // their events (and the World's) appended.
  // The initial stone's changes before batch_end were applied already (step_world); those
  // after it apply here, one by one, in order with the rest.
  void apply_board_changes(double t_s, std::int64_t stamp_ns, std::size_t batch_end,
                           std::vector<SegmentEvent>& events);
  // reset, set_state or set_angular_velocity of one stone applied to the World at t_s on its
  // own (a reset of the removed initial stone adds it again), with its events.
  void apply_state_change(const Change& change, double t_s, std::int64_t stamp_ns,
                          std::vector<SegmentEvent>& events);

  // Segment events (stone_simulation_events.cpp).
  // A World event -> a segment event (not yet numbered), checked finite; throws otherwise.
  SegmentEvent segment_event(const WorldEvent& event) const;
  // Numbers and appends events (the World's from segment_event, and commands'); tracks rest.
  void commit_events(std::vector<SegmentEvent>& events, UpdateResult& result);
  // The instant of a World time as a stamp (rounded down to a whole ns) and its offset.
  void split_world_time(double t_s, std::int64_t& stamp_ns, double& offset_s) const;
  void begin_segment(EventReason reason, std::int64_t stamp_ns, UpdateResult& result);
  // The event of a change from outside at stamp_ns (not yet numbered): `stone` in the state the
  // change makes, with its outputs (checked finite; throws otherwise).
  static SegmentEvent command_event(std::int64_t stamp_ns, EventReason reason,
                                    const std::string& stone, const RigidBodyState& state,
                                    const MotionModel& model);
  // The World's events of a command at its instant appended to `events` with the command's own
  // events (`commands`) after the wake the World reports first and before the rest.
  void append_after_wake(const std::vector<WorldEvent>& world_events,
                         std::vector<SegmentEvent> commands,
                         std::vector<SegmentEvent>& events) const;
  // Appends a numbered event (a new segment) with the given first state.
  void announce(EventReason reason, std::int64_t stamp_ns, const RigidBodyState& state,
                const StateOutput& output, UpdateResult& result);

  CheckedConfig checked_;
  std::unique_ptr<Integrator> integrator_;
  SimClock clock_;
  RigidBodyState state_;
  StateOutput output_;         // of state_, unless output_stale_
  bool output_stale_ = false;  // state_ moved on since output_ was computed
  FlightCache flight_cache_;   // the stone's: what the integrator carries between its steps
  std::int64_t start_ns_ = 0;
  std::int64_t segment_start_ns_ = 0;
  std::uint32_t segment_ = 0;
  // A step failed on state_ and no change has replaced it since: there is no new state to
  // publish, also not after a time jump (it would re-stamp the old one).
  bool held_ = false;
  std::string failure_;           // why, for requests
  bool failure_reported_ = true;  // the next request's answer has carried failure_
  std::deque<Change> pending_;
  bool behind_ = false;  // the last update left steps for the next (its budget was spent)
  bool paused_ = false;
  std::int64_t steps_queued_ = 0;  // ticks ~step asked for, not yet taken
  bool resync_ = false;            // unpaused while following ROS time: skip the paused interval
  // With the board.
  std::optional<World> world_;
  std::int64_t epoch_ns_ = 0;
  std::int64_t rest_since_ns_ = -1;       // first whole ns at rest (the rest event's, rounded up)
  std::vector<WorldEvent> world_events_;  // the events of the step in progress
  StoneId initial_id_;                    // the initial stone's World id
  bool initial_removed_ = false;          // by ~remove or ~clear, until ~reset
  std::vector<PlacedStone> placed_;
  std::vector<std::size_t> body_of_placed_;  // the World body of each placed_ entry
  int next_number_[2] = {1, 1};              // the next ~place number per colour (black, white)
  std::string board_note_;                   // a placement the World refused, for the next answer
  // The World is part-way to the next grid time (a step cut short by the budget); its events
  // so far are in world_events_.
  bool mid_step_ = false;
  // The set-down planner's view of the board once pending_[0 .. applied) apply (check_room): a
  // ~place replaying every waiting request cost O(waiting x stones). Valid while the World and
  // the queue change only by requests queued: every step (and a hold or a World reset)
  // invalidates it.
  struct PlannedLayout {
    std::vector<PlanStone> stones;
    std::vector<std::string> names;  // each stone's name, as stones
    std::size_t applied = 0;
    bool valid = false;
  };
  PlannedLayout planned_;
};

}  // namespace virtual_go
