#include "virtual_go/sim/stone_simulation.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/world/stone_placement.h"

namespace virtual_go {
namespace {

// 1 s behind ROS time: skip rather than catch up.
constexpr std::int64_t kMaxLagNs = kNanosecondsPerSecond;

constexpr char kApplied[] = "applied at the next physics step";
// World work units (integrator steps, searches, impacts) between two looks at an update's budget:
// about a millisecond of hard contact (a plane-contact step costs a few microseconds).
constexpr long kWorkPerSlice = 500;

EventReason event_reason(WorldEventKind kind) {
  switch (kind) {
    case WorldEventKind::impact:
      return EventReason::impact;
    case WorldEventKind::slide:
      return EventReason::slide;
    case WorldEventKind::roll:
      return EventReason::roll;
    case WorldEventKind::rim:
      return EventReason::rim;
    case WorldEventKind::lift_off:
      return EventReason::lift_off;
    case WorldEventKind::rest:
      return EventReason::rest;
    case WorldEventKind::wake:
      return EventReason::wake;
  }
  throw std::logic_error("unknown world event kind");
}

}  // namespace

StoneSimulation::StoneSimulation(const StoneConfig& config)
    : StoneSimulation(check_config(config)) {}

StoneSimulation::StoneSimulation(CheckedConfig checked)
    : checked_(std::move(checked)),
      integrator_(checked_.integrator->make(*checked_.integrator, checked_.setup)),
      clock_(checked_.dt_ns, std::max(kMaxLagNs, 2 * checked_.dt_ns)),
      state_(checked_.initial_state),
      output_(state_output(checked_.setup.model, checked_.initial_state)) {
  // No stone until the start: a state the World refuses (tests reach states the checks refuse)
  // then holds the simulation instead of escaping from here.
  if (checked_.world) world_.emplace(*checked_.world, std::vector<RigidBodyState>{}, 0.0);
}

void StoneSimulation::check_clear_of_board(const std::string& field, const RigidBodyState& state,
                                           const BoardDistance* board) const {
  if (!world_) return;
  const BoardContact contact = (board ? *board : world_->board_distance()).nearest(state);
  const double tolerance = world_->config().options.time_of_impact.touch_tolerance_m;
  if (contact.lens.gap_m < -tolerance) {
    throw InvalidArgument(field, field + ": the stone would overlap the " +
                                     (contact.on_table() ? std::string("table") : "board") +
                                     " by " + format_value(-contact.lens.gap_m) + " m, at most " +
                                     format_value(tolerance) + " m is allowed");
  }
}

void StoneSimulation::split_world_time(double t_s, std::int64_t& stamp_ns, double& offset_s) const {
  // Relative to the epoch t_s resolves far below a nanosecond; the offset is what remains of it
  // after the whole nanoseconds, in [0, 1e-9).
  std::int64_t k = static_cast<std::int64_t>(std::floor(to_nanoseconds(t_s)));
  double offset = t_s - to_seconds(k);
  while (offset < 0.0) offset = t_s - to_seconds(--k);
  while (offset >= 1e-9) offset = t_s - to_seconds(++k);
  stamp_ns = epoch_ns_ + k;
  offset_s = offset;
}

SegmentEvent StoneSimulation::segment_event(const WorldEvent& event) const {
  SegmentEvent out;
  split_world_time(event.time_s, out.stamp_ns, out.time_offset_s);
  out.reason = event_reason(event.kind);
  out.detail = world_event_detail_name(event.detail);
  out.stone = name_of(event.id);
  if (event.other) out.other_stone = name_of(*event.other);
  out.state = event.state;
  out.output = state_output(model_of(event.id), event.state);  // throws if not finite
  return out;
}

const std::string& StoneSimulation::stone_name(std::size_t index) const {
  // One stone today, named by its frame (~stone_frame, "stone" by default).
  if (index != 0) throw std::logic_error("stone index " + std::to_string(index) + " of 1 stone");
  return checked_.config.stone_frame;
}

std::string StoneSimulation::name_of(StoneId id) const {
  if (id == initial_id_) return stone_name(0);
  for (const PlacedStone& p : placed_) {
    if (p.id == id) return p.name;
  }
  return "";
}

const MotionModel& StoneSimulation::model_of(StoneId id) const {
  for (std::size_t k = 0; k < placed_.size(); ++k) {
    if (placed_[k].id == id) return world_->body_model(body_of_placed_[k]).setup().model;
  }
  return checked_.setup.model;
}

void StoneSimulation::reset_world(const RigidBodyState& state, double t_s) {
  planned_.valid = false;
  // World::reset keeps only stones of the config's body: the placed stones are added back where
  // they are, at rest if they rested (a stone set down flat on the board rests at once).
  std::vector<RigidBodyState> placed_states;
  for (const PlacedStone& p : placed_) placed_states.push_back(world_->state(p.id));
  if (initial_removed_) {
    world_->reset({}, t_s);
  } else {
    world_->reset({state}, t_s);
    initial_id_ = world_->id(0);
  }
  // Their events at t_s (a resting stone re-added rests at once) are not reported: the stones
  // only go on, on the new time line.
  std::vector<WorldEvent> ignored;
  for (std::size_t k = 0; k < placed_.size(); ++k) {
    placed_[k].id = world_->add_stone(body_of_placed_[k], placed_states[k], t_s, ignored);
  }
}

void StoneSimulation::commit_events(std::vector<SegmentEvent>& events, UpdateResult& result) {
  for (SegmentEvent& event : events) {
    if (event.reason != EventReason::start) ++segment_;
    event.segment = segment_;
    // Rest and the age of the motion (~auto_reset_*) are those of the initial stone.
    if (event.stone != stone_name(0)) {
      result.events.push_back(std::move(event));
      continue;
    }
    if (event.reason == EventReason::rest) {
      rest_since_ns_ = event.stamp_ns + (event.time_offset_s > 0.0 ? 1 : 0);
    } else {
      rest_since_ns_ = -1;
    }
    // The age ~auto_reset_period counts is that of the motion given from outside.
    if (event.reason < EventReason::impact) segment_start_ns_ = event.stamp_ns;
    result.events.push_back(std::move(event));
  }
}

void StoneSimulation::restart_world(std::int64_t stamp_ns, UpdateResult& result) {
  if (!world_) return;
  epoch_ns_ = stamp_ns;
  rest_since_ns_ = -1;
  reset_world(state_, 0.0);
  world_events_.clear();
  mid_step_ = false;
  world_->advance_to(0.0, world_events_);
  std::vector<SegmentEvent> events;
  for (const WorldEvent& e : world_events_) events.push_back(segment_event(e));
  commit_events(events, result);
  if (initial_removed_) return;
  state_ = world_->state(initial_id_);
  output_ = state_output(checked_.setup.model, state_);
  output_stale_ = false;
}

std::string StoneSimulation::answer() {
  if (!board_note_.empty()) {
    std::string note = std::string(kApplied) + "; note: " + board_note_;
    board_note_.clear();
    return note;
  }
  if (failure_reported_) return kApplied;
  failure_reported_ = true;
  return std::string(kApplied) + "; note: " + failure_ +
         (held_ ? " (the state is held until a reset or set_state replaces it)" : "");
}

void StoneSimulation::enqueue(Change change) {
  // Without steps (ROS time standing still, e.g. use_sim_time without /clock) nothing takes
  // requests off the queue: bound it rather than let a caller fill the memory.
  if (pending_.size() >= kMaxPendingRequests) {
    throw RequestRefused(
        "refused: " + std::to_string(pending_.size()) +
        " requests already wait for the next physics step (the limit): " +
        (paused_ ? std::string("the simulation is paused (~step or ~unpause takes them)")
                 : std::string("ROS time has not advanced by a step since they came (under "
                               "use_sim_time, is /clock published?)")));
  }
  pending_.push_back(std::move(change));
}

void StoneSimulation::require_board(const std::string& request) const {
  if (!world_ || !world_->config().board_enabled) {
    throw RequestRefused("refused: " + request +
                         " needs the board (~board/enabled is false: there is only the stone '" +
                         stone_name(0) + "')");
  }
}

std::string StoneSimulation::place(const PlaceRequest& request, std::string& answer_out) {
  require_board("~place");
  const StoneColor color = parse_stone_color(request.color);
  Change change;
  change.reason = EventReason::place;
  change.color = color;
  std::optional<SetDownPlan> set_down;  // a set-down's plan, checked for room
  if (!request.point.empty()) {
    if (world_->config().board.lines != kGoLines) {
      throw InvalidArgument("point", "point: Go points need a board of " +
                                         std::to_string(kGoLines) + " lines, this one has " +
                                         std::to_string(world_->config().board.lines) +
                                         " (give a pose instead)");
    }
    change.point = parse_gtp_point(request.point);
    const double h = request.drop_height_m;
    if (!std::isfinite(h) || h < 0.0 || h > kMaxDropHeightM) {
      throw InvalidArgument("drop_height", "drop_height: must be in [0, " +
                                               format_value(kMaxDropHeightM) + "] m, got " +
                                               format_value(h));
    }
    check_velocity("twist.linear", request.velocity_world, checked_.limits);
    check_angular_velocity("twist.angular", request.angular_velocity_world, checked_.limits);
    change.drop_height_m = h;
    change.velocity_world = request.velocity_world;
    change.angular_velocity_world = request.angular_velocity_world;
    if (h == 0.0 && change.velocity_world.isZero(0.0) &&
        change.angular_velocity_world.isZero(0.0)) {
      set_down = check_room(world_->color_body(color), *change.point);
    }
  } else {
    // The colour's body is made once, here if not yet (World::color_body): its lens decides
    // whether the pose overlaps the board.
    const WorldBodyModel& body = world_->body_model(world_->color_body(color));
    const Eigen::Vector4d q = request.orientation_xyzw.isZero(0.0)
                                  ? Eigen::Vector4d(0.0, 0.0, 0.0, 1.0)
                                  : request.orientation_xyzw;
    change.state =
        state_from_request({"pose.position", "pose.orientation", "twist.linear", "twist.angular"},
                           body.setup().model, request.position_world, q, request.velocity_world,
                           request.angular_velocity_world, checked_.limits);
    check_clear_of_board("pose.position", change.state, &body.board());
  }
  int& number = next_number_[color == StoneColor::black ? 0 : 1];
  change.name = stone_color_name(color) + "_" + std::to_string(number);
  enqueue(change);  // may refuse: the number is taken only once the request is accepted
  ++number;
  if (set_down) planned_after(*set_down);
  answer_out = answer();
  return change.name;
}

std::string StoneSimulation::remove(const std::string& name_or_point, std::string& answer_out) {
  require_board("~remove");
  const std::vector<std::string> present = names_after_pending();
  if (name_or_point == stone_name(0)) {
    (void)request_target(name_or_point);  // refuses it if removed already
  }
  std::string name;
  const auto pending_place = [&](const std::string& n) {
    return std::any_of(pending_.begin(), pending_.end(), [&](const Change& c) {
      return c.reason == EventReason::place && c.name == n;
    });
  };
  const auto is_placed = [&](const std::string& n) {
    return std::any_of(placed_.begin(), placed_.end(),
                       [&](const PlacedStone& p) { return p.name == n; });
  };
  if (name_or_point == stone_name(0) || is_placed(name_or_point) || pending_place(name_or_point)) {
    name = name_or_point;
    if (std::find(present.begin(), present.end(), name) == present.end()) {
      (void)request_target(name);  // removed by a request waiting: refused, naming it
    }
  } else {
    GoPoint point;
    try {
      point = parse_gtp_point(name_or_point);
    } catch (const InvalidArgument&) {
      throw InvalidArgument("name", "name: no stone named '" + name_or_point +
                                        "' and not a Go point \"A1\" ... \"T19\"");
    }
    name = stone_at(point);
    if (name.empty()) {
      throw InvalidArgument("name", "name: no stone at " + gtp_name(point));
    }
  }
  Change change;
  change.reason = EventReason::remove;
  change.name = name;
  enqueue(change);
  answer_out = answer();
  return name;
}

std::string StoneSimulation::stone_at(GoPoint point) const {
  if (!world_) return "";
  for (auto it = pending_.rbegin(); it != pending_.rend(); ++it) {
    if (it->reason == EventReason::place && it->point && *it->point == point) return it->name;
  }
  if (world_->config().board.lines != kGoLines) return "";
  const BoardGeometry& board = world_->config().board;
  const Eigen::Vector3d at = go_point_world(board, point);
  const std::vector<std::string> present = names_after_pending();
  std::string name;
  double best = std::numeric_limits<double>::infinity();
  const auto consider = [&](const std::string& n, StoneId id) {
    // Only stones still there once the waiting requests apply.
    if (std::find(present.begin(), present.end(), n) == present.end()) return;
    const Eigen::Vector3d x = world_->state(id).position_world;
    const std::optional<GoPoint> nearest = nearest_go_point(board, x);
    const double d = (x - at).head<2>().norm();
    if (nearest && *nearest == point && d < best) {
      best = d;
      name = n;
    }
  };
  if (!initial_removed_) consider(stone_name(0), initial_id_);
  for (const PlacedStone& p : placed_) consider(p.name, p.id);
  return name;
}

std::string StoneSimulation::clear() {
  require_board("~clear");
  Change change;
  change.reason = EventReason::clear;
  enqueue(change);
  return answer();
}

void StoneSimulation::apply_board_changes(double t_s, std::int64_t stamp_ns, std::size_t batch_end,
                                          std::vector<SegmentEvent>& events) {
  World& world = *world_;
  const auto command_event = [&](EventReason reason, const std::string& name, StoneId id) {
    SegmentEvent e;
    e.stamp_ns = stamp_ns;
    e.reason = reason;
    e.stone = name;
    e.state = world.state(id);
    e.output = state_output(model_of(id), e.state);
    events.push_back(std::move(e));
  };
  const auto remove_placed = [&](std::size_t k, EventReason reason) {
    command_event(reason, placed_[k].name, placed_[k].id);
    std::vector<WorldEvent> none;
    world.remove_stone(placed_[k].id, t_s, none);
    placed_.erase(placed_.begin() + static_cast<std::ptrdiff_t>(k));
    body_of_placed_.erase(body_of_placed_.begin() + static_cast<std::ptrdiff_t>(k));
  };
  const auto remove_initial = [&](EventReason reason) {
    if (initial_removed_) return;
    command_event(reason, stone_name(0), initial_id_);
    std::vector<WorldEvent> none;
    world.remove_stone(initial_id_, t_s, none);
    initial_removed_ = true;
    rest_since_ns_ = -1;
  };
  for (std::size_t n = 0; n < pending_.size(); ++n) {
    const Change& change = pending_[n];
    if (!change.on_board()) {
      // The initial stone's changes before batch_end went to the World in one (step_world).
      if (!change.initial_stone() || n >= batch_end) {
        apply_state_change(change, t_s, stamp_ns, events);
      }
      continue;
    }
    if (change.reason == EventReason::clear) {
      remove_initial(EventReason::clear);
      while (!placed_.empty()) remove_placed(0, EventReason::clear);
      continue;
    }
    if (change.reason == EventReason::remove) {
      if (change.name == stone_name(0)) {
        remove_initial(EventReason::remove);
        continue;
      }
      for (std::size_t k = 0; k < placed_.size(); ++k) {
        if (placed_[k].name == change.name) {
          remove_placed(k, EventReason::remove);
          break;
        }
      }
      continue;  // removed already (twice asked, or cleared): nothing to do
    }
    std::vector<WorldEvent> world_events;
    StoneId id;
    try {
      if (!change.point) {
        id = world.add_stone(change.color, change.state, t_s, world_events);
      } else if (change.drop_height_m == 0.0 && change.velocity_world.isZero(0.0) &&
                 change.angular_velocity_world.isZero(0.0)) {
        id = set_down_stone(world, change.color, *change.point, t_s, world_events).id;
      } else {
        id = drop_stone(world, change.color, *change.point, change.drop_height_m, t_s, world_events,
                        change.velocity_world, change.angular_velocity_world)
                 .id;
      }
    } catch (const InvalidArgument& e) {
      // Nothing was added: say so to the next caller rather than hold the simulation.
      board_note_ = change.name + " was not placed: " + e.what();
      continue;
    }
    placed_.push_back({change.name, change.color, id});
    body_of_placed_.push_back(world.body_of(id));
    command_event(EventReason::place, change.name, id);
    for (const WorldEvent& e : world_events) events.push_back(segment_event(e));
  }
}

void StoneSimulation::apply_state_change(const Change& change, double t_s, std::int64_t stamp_ns,
                                         std::vector<SegmentEvent>& events) {
  World& world = *world_;
  std::vector<WorldEvent> world_events;
  const auto command = [&](const std::string& name, StoneId id) {
    SegmentEvent e;
    e.stamp_ns = stamp_ns;
    e.reason = change.reason;
    e.stone = name;
    e.state = world.state(id);
    e.output = state_output(model_of(id), e.state);
    return e;
  };
  if (change.initial_stone() && initial_removed_) {
    // Removed earlier: only a reset brings it back (the others were refused when asked, unless
    // a reset came first).
    if (change.reason != EventReason::reset) return;
    initial_id_ = world.add_stone(0, checked_.initial_state, t_s, world_events);
    initial_removed_ = false;
    events.push_back(command(stone_name(0), initial_id_));
    for (const WorldEvent& e : world_events) events.push_back(segment_event(e));
    return;
  }
  StoneId id = initial_id_;
  std::string name = stone_name(0);
  if (!change.initial_stone()) {
    const auto it = std::find_if(placed_.begin(), placed_.end(),
                                 [&](const PlacedStone& p) { return p.name == change.name; });
    if (it == placed_.end()) return;  // removed by a request before it in this step
    id = it->id;
    name = it->name;
  }
  const MotionModel& model = model_of(id);
  RigidBodyState next = change.state;
  if (change.reason == EventReason::reset) next = checked_.initial_state;
  if (change.reason == EventReason::set_angular_velocity) {
    const RigidBodyState& now = world.state(id);
    const Eigen::Vector3d omega_world = change.frame == RequestFrame::body
                                            ? rotate_without_overflow(now.orientation, change.omega)
                                            : change.omega;
    next = with_angular_velocity_world(model, now, omega_world);
  }
  world.set_state(id, next, t_s, world_events);  // a resting stone wakes first
  std::size_t i = 0;
  for (; i < world_events.size() && world_events[i].kind == WorldEventKind::wake; ++i) {
    events.push_back(segment_event(world_events[i]));
  }
  SegmentEvent e = command(name, id);
  e.state = next;
  e.output = state_output(model, next);
  events.push_back(std::move(e));
  for (; i < world_events.size(); ++i) events.push_back(segment_event(world_events[i]));
}

std::string StoneSimulation::reset() {
  enqueue({EventReason::reset, checked_.initial_state, {}, {}});
  return answer();
}

std::string StoneSimulation::set_angular_velocity(const Eigen::Vector3d& omega,
                                                  const std::string& frame,
                                                  const std::string& name) {
  const std::string target = request_target(name);
  const StoneConfig& c = checked_.config;
  const RequestFrame f =
      request_frame("frame", frame, c.world_frame, target.empty() ? c.stone_frame : target);
  check_angular_velocity("angular_velocity", omega, checked_.limits);
  if (held_ && !replacement_due()) {
    // It would only change a state that cannot move: say so instead of "applied".
    failure_reported_ = true;
    throw RequestRefused("refused: the state is held since " + failure_ +
                         "; ~reset or ~set_state replaces it, after which angular velocity "
                         "requests apply again");
  }
  Change change;
  change.reason = EventReason::set_angular_velocity;
  change.omega = omega;
  change.frame = f;
  change.name = target;
  enqueue(change);
  return answer();
}

std::string StoneSimulation::set_state(const Eigen::Vector3d& position_world,
                                       const Eigen::Vector4d& orientation_xyzw,
                                       const Eigen::Vector3d& velocity_world,
                                       const Eigen::Vector3d& angular_velocity_world,
                                       const std::string& name) {
  const std::string target = request_target(name);
  const StateFieldNames fields{"pose.position", "pose.orientation", "twist.linear",
                               "twist.angular"};
  Change change;
  change.reason = EventReason::set_state;
  change.omega = Eigen::Vector3d::Zero();
  change.name = target;
  if (target.empty()) {
    change.state =
        state_from_request(fields, checked_.setup.model, position_world, orientation_xyzw,
                           velocity_world, angular_velocity_world, checked_.limits);
    check_clear_of_board("pose.position", change.state);
  } else {
    // A placed stone (or one waiting to be): its colour's body.
    const auto placed = std::find_if(placed_.begin(), placed_.end(),
                                     [&](const PlacedStone& p) { return p.name == target; });
    StoneColor color = StoneColor::black;
    if (placed != placed_.end()) {
      color = placed->color;
    } else {
      for (const Change& c : pending_) {
        if (c.reason == EventReason::place && c.name == target) color = c.color;
      }
    }
    const WorldBodyModel& body = world_->body_model(world_->color_body(color));
    change.state = state_from_request(fields, body.setup().model, position_world, orientation_xyzw,
                                      velocity_world, angular_velocity_world, checked_.limits);
    check_clear_of_board("pose.position", change.state, &body.board());
  }
  enqueue(change);
  return answer();
}

std::vector<std::string> StoneSimulation::names_after_pending() const {
  std::vector<std::string> names;
  if (!initial_removed_) names.push_back(stone_name(0));
  for (const PlacedStone& p : placed_) names.push_back(p.name);
  const auto drop = [&](const std::string& n) {
    names.erase(std::remove(names.begin(), names.end(), n), names.end());
  };
  for (const Change& c : pending_) {
    if (c.reason == EventReason::clear) names.clear();
    if (c.reason == EventReason::remove) drop(c.name);
    if (c.reason == EventReason::place) names.push_back(c.name);
    if (c.reason == EventReason::reset && c.initial_stone()) {
      drop(stone_name(0));
      names.insert(names.begin(), stone_name(0));
    }
  }
  return names;
}

std::string StoneSimulation::request_target(const std::string& name) const {
  if (name.empty() && !world_) return "";  // without the board there is the one stone
  const std::string target = name.empty() ? stone_name(0) : name;
  const std::vector<std::string> names = names_after_pending();
  if (std::find(names.begin(), names.end(), target) != names.end()) {
    return target == stone_name(0) ? "" : target;
  }
  // Gone (removed, cleared) or never there: say which, and what there is (the first few).
  const bool was_here = target == stone_name(0) ||
                        std::any_of(placed_.begin(), placed_.end(),
                                    [&](const PlacedStone& p) { return p.name == target; }) ||
                        std::any_of(pending_.begin(), pending_.end(), [&](const Change& c) {
                          return c.reason == EventReason::place && c.name == target;
                        });
  std::string message = "name: " + quote_user_text(target) +
                        (was_here ? std::string(" is removed (by ~remove or ~clear") +
                                        (target == stone_name(0) ? "; ~reset puts it back)" : ")")
                                  : std::string(" is no stone"));
  constexpr std::size_t kListed = 12;
  if (names.empty()) {
    message += "; there are no stones";
  } else {
    message += "; the stones are";
    for (std::size_t k = 0; k < names.size() && k < kListed; ++k) {
      message += (k ? ", " : " ") + names[k];
    }
    if (names.size() > kListed) {
      message += " and " + std::to_string(names.size() - kListed) + " more";
    }
  }
  throw InvalidArgument("name", message);
}

const std::vector<PlanStone>& StoneSimulation::planned_layout() {
  PlannedLayout& l = planned_;
  if (!l.valid || l.applied > pending_.size()) {
    // The planner's layout now; the requests waiting follow, in order.
    l.stones = plan_stones(*world_);
    l.names.assign(l.stones.size(), "");
    for (std::size_t i = 0; i < l.stones.size(); ++i) l.names[i] = name_of(l.stones[i].id);
    l.applied = 0;
    l.valid = true;
  }
  for (; l.applied < pending_.size(); ++l.applied) plan_change(pending_[l.applied]);
  return l.stones;
}

void StoneSimulation::plan_change(const Change& c) {
  std::vector<PlanStone>& stones = planned_.stones;
  std::vector<std::string>& names = planned_.names;
  const auto drop = [&](const std::string& n) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] != n) continue;
      names.erase(names.begin() + static_cast<std::ptrdiff_t>(i));
      stones.erase(stones.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  };
  const auto teleport = [&](const std::string& n, const RigidBodyState& state) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] != n) continue;
      stones[i].centre_xy = state.position_world.head<2>();
      stones[i].z_m = state.position_world.z();
      stones[i].movable = false;  // moving, or resting only after the step
    }
  };
  if (c.reason == EventReason::clear) {
    stones.clear();
    names.clear();
  } else if (c.reason == EventReason::remove) {
    drop(c.name);
  } else if (c.reason == EventReason::place && c.point && c.drop_height_m == 0.0 &&
             c.velocity_world.isZero(0.0) && c.angular_velocity_world.isZero(0.0)) {
    try {
      apply_plan(stones, plan_set_down(*world_, world_->color_body(c.color), *c.point, stones));
      names.push_back(c.name);
    } catch (const InvalidArgument&) {
      // That one will be refused when it applies (the layout moved since it was accepted).
    }
  } else if (c.reason == EventReason::place && c.point) {
    // A drop nudges as a set-down does, and lands where it is aimed; within this step it is
    // where drop_stone lets it go, drop_height_m above a stone lying there (a set-down after it
    // meets it in the air, or not at all: layout_around's height band).
    SetDownPlan plan = plan_drop(*world_, world_->color_body(c.color), *c.point, stones);
    plan.stone.z_m += c.drop_height_m;
    apply_plan(stones, plan);
    names.push_back(c.name);
  } else if (c.reason == EventReason::place) {
    // By pose: where the pose puts it, never nudged (it rests only after the step, if at all).
    // A stone in the air is out of a set-down's way by layout_around's height band; one lying
    // on the board is in it.
    stones.push_back(
        PlanStone{StoneId{}, c.state.position_world.head<2>(), c.state.position_world.z(),
                  world_->body_model(world_->color_body(c.color)).lens().half_width(), false});
    names.push_back(c.name);
  } else if (c.reason == EventReason::set_state) {
    teleport(c.name.empty() ? stone_name(0) : c.name, c.state);
  } else if (c.reason == EventReason::reset) {
    drop(stone_name(0));
    const RigidBodyState& s = checked_.initial_state;
    stones.push_back(PlanStone{StoneId{}, s.position_world.head<2>(), s.position_world.z(),
                               world_->body_model(0).lens().half_width(), false});
    names.push_back(stone_name(0));
  } else if (c.reason == EventReason::set_angular_velocity) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == (c.name.empty() ? stone_name(0) : c.name)) stones[i].movable = false;
    }
  }
}

SetDownPlan StoneSimulation::check_room(std::size_t body, GoPoint point) {
  return plan_set_down(*world_, body, point, planned_layout());  // throws "point": no room
}

void StoneSimulation::planned_after(const SetDownPlan& plan) {
  // Only onto the layout of every request before it; else the next check_room plans it anew.
  if (!planned_.valid || planned_.applied + 1 != pending_.size()) return;
  apply_plan(planned_.stones, plan);
  planned_.names.push_back(pending_.back().name);
  ++planned_.applied;
}

void StoneSimulation::replace_state(const RigidBodyState& state) {
  StateOutput output = state_output(checked_.setup.model, state);  // throws: nothing changed
  state_ = state;
  output_ = output;
  output_stale_ = false;
  flight_cache_.invalidate();  // the integrator must not continue the old motion
}

void StoneSimulation::begin_segment(EventReason reason, std::int64_t stamp_ns,
                                    UpdateResult& result) {
  announce(reason, stamp_ns, state_, output_, result);
}

void StoneSimulation::announce(EventReason reason, std::int64_t stamp_ns,
                               const RigidBodyState& state, const StateOutput& output,
                               UpdateResult& result) {
  if (reason != EventReason::start) ++segment_;
  if (reason != EventReason::held) segment_start_ns_ = stamp_ns;
  SegmentEvent event;
  event.stamp_ns = stamp_ns;
  event.segment = segment_;
  event.reason = reason;
  event.stone = stone_name(0);
  event.state = state;
  event.output = output;
  if (reason == EventReason::held) event.detail = failure_;
  result.events.push_back(std::move(event));
}

bool StoneSimulation::auto_reset_due(std::int64_t next_ns) const {
  if (initial_removed_) return false;  // ~reset alone brings it back
  const std::int64_t auto_reset_ns = checked_.auto_reset_ns;
  if (auto_reset_ns > 0 && next_ns - segment_start_ns_ >= auto_reset_ns) return true;
  const std::int64_t after_rest_ns = checked_.auto_reset_after_rest_ns;
  return world_ && after_rest_ns > 0 && rest_since_ns_ >= 0 &&
         next_ns - rest_since_ns_ >= after_rest_ns;
}

bool StoneSimulation::replacement_due() const {
  if (auto_reset_due(clock_.next_time_ns())) return true;
  return std::any_of(pending_.begin(), pending_.end(),
                     [](const Change& change) { return change.replaces_state(); });
}

void StoneSimulation::hold(const std::string& cause, UpdateResult& result) {
  std::string failure =
      "the physics step after " + stamp_text(clock_.time_ns()) + " s failed: " + cause;
  if (!pending_.empty()) {
    failure +=
        " (" + std::to_string(pending_.size()) + " request(s) due at that step were not applied)";
    pending_.clear();
    planned_.valid = false;
  }
  held_ = true;
  failure_ = failure;
  failure_reported_ = false;
  flight_cache_.invalidate();  // it may have moved on with the step that failed
  result.error = failure;
  if (!result.advanced) result.stamp_ns = clock_.time_ns();
  // Announced on ~events too: the state stays the last one published (at the clock's time),
  // with the cause in detail. A state whose outputs are not finite is not announced.
  try {
    announce(EventReason::held, clock_.time_ns(), state_,
             state_output(checked_.setup.model, state_), result);
  } catch (const std::exception&) {
  }
}

UpdateResult StoneSimulation::update(std::int64_t now_ns) noexcept {
  UnlimitedBudget unlimited;
  return update(now_ns, unlimited);
}

UpdateResult StoneSimulation::update(std::int64_t now_ns, UpdateBudget& budget) noexcept {
  UpdateResult result;
  // Whatever fails (a step, a change, an output that would not be finite) holds the state:
  // nothing leaves this function, so no input can stop the node.
  try {
    advance_to(now_ns, budget, result);
  } catch (const std::exception& e) {
    hold(e.what(), result);
  } catch (...) {
    hold("an unknown exception", result);
  }
  return result;
}

void StoneSimulation::jump_to(std::int64_t now_ns, const std::string& detail,
                              UpdateResult& result) {
  // The state keeps going from where it was, but on the new time line: a new segment, and
  // nothing stamped on the old one is published again.
  clock_.restart(now_ns);
  // A held state is only re-timed (so a reset takes effect near ROS time): announcing or
  // publishing it would present the stale state as new.
  if (held_) return;
  if (!initial_removed_) {
    begin_segment(EventReason::time_jump, now_ns, result);
    result.events.back().detail = detail;
  }
  behind_ = false;
  restart_world(now_ns, result);
  result.advanced = true;
  result.stamp_ns = clock_.time_ns();
}

std::int64_t StoneSimulation::take_steps(std::int64_t steps, UpdateBudget& budget,
                                         UpdateResult& result) {
  std::int64_t taken = 0;
  for (; taken < steps; ++taken) {
    // The first step is always taken (the simulation moves on however slow a step is).
    if (taken > 0 && budget.spent()) break;
    if (held_ && !replacement_due()) {
      // Nothing can move the held state; the clock keeps to ROS time so that a reset
      // takes effect at the next grid time, and nothing is published.
      clock_.step();
      continue;
    }
    try {
      if (!step(result, budget)) break;
    } catch (const std::exception& e) {
      hold(e.what(), result);
      continue;
    }
    held_ = false;
    result.advanced = true;
    result.stamp_ns = clock_.time_ns();
  }
  // What messages show of the state to publish: once per update, not at every step (the
  // integrator refuses a non-finite state at every step; the derived numbers are checked
  // here, before anything is published).
  if (result.advanced && output_stale_) {
    try {
      output_ = state_output(checked_.setup.model, state_);
      output_stale_ = false;
    } catch (const std::exception& e) {
      result.advanced = false;
      hold(e.what(), result);
    }
  }
  return taken;
}

void StoneSimulation::advance_to(std::int64_t now_ns, UpdateBudget& budget, UpdateResult& result) {
  if (paused_ && clock_.started()) {
    // Only the ticks ~step queued, whatever ROS time says.
    if (steps_queued_ > 0) steps_queued_ -= take_steps(steps_queued_, budget, result);
    return;
  }
  const SimClock::Plan plan = clock_.plan(now_ns);
  if (resync_ && plan.action != SimClock::Action::start) {
    // The first update after unpause() following ROS time: the paused interval is not
    // simulated (pausing would otherwise only delay the motion), so the time line skips it.
    resync_ = false;
    if (plan.action != SimClock::Action::wait) {
      jump_to(now_ns, "unpaused", result);
      return;
    }
  }
  switch (plan.action) {
    case SimClock::Action::wait:
      return;
    case SimClock::Action::start:
      clock_.restart(now_ns);
      start_ns_ = now_ns;
      replace_state(checked_.initial_state);
      begin_segment(EventReason::start, now_ns, result);
      restart_world(now_ns, result);
      result.advanced = true;
      result.stamp_ns = clock_.time_ns();
      return;
    case SimClock::Action::jump_back:
    case SimClock::Action::jump_forward:
      // Forward after updates the budget cut short: the physics, not ROS time, is to blame.
      jump_to(now_ns,
              behind_ && plan.action == SimClock::Action::jump_forward ? "physics_behind" : "",
              result);
      return;
    case SimClock::Action::advance: {
      const std::int64_t taken = take_steps(plan.steps, budget, result);
      if (taken < plan.steps) {
        result.steps_deferred = plan.steps - taken;
        result.behind_ns = now_ns - clock_.time_ns();
      }
      behind_ = result.steps_deferred > 0;
      return;
    }
  }
}

std::string StoneSimulation::pause() {
  if (paused_) return "already paused";
  paused_ = true;
  resync_ = false;
  return "paused at " + stamp_text(clock_.time_ns()) +
         " s: no step is taken until ~step or ~unpause; requests wait for the next step";
}

std::string StoneSimulation::unpause() {
  if (!paused_) return "not paused";
  std::string answer = "unpaused at " + stamp_text(clock_.time_ns()) + " s";
  if (steps_queued_ > 0) {
    answer += "; the " + std::to_string(steps_queued_) + " tick(s) ~step queued are dropped";
  }
  paused_ = false;
  steps_queued_ = 0;
  // Following ROS time: the paused interval is skipped at the next update (see pause()).
  resync_ = !checked_.config.publish_clock && clock_.started();
  return answer;
}

std::string StoneSimulation::step(std::int64_t ticks) {
  if (ticks < 1) {
    throw InvalidArgument("ticks", "ticks: must be at least 1, got " + std::to_string(ticks));
  }
  if (ticks > kMaxStepTicks - steps_queued_) {
    throw InvalidArgument("ticks", "ticks: at most " + std::to_string(kMaxStepTicks) +
                                       " may be queued (" + std::to_string(steps_queued_) +
                                       " already are), got " + std::to_string(ticks));
  }
  if (!paused_) {
    throw RequestRefused("refused: ~step needs the simulation paused (call ~pause first)");
  }
  steps_queued_ += ticks;
  return std::to_string(ticks) + " tick(s) of " + std::to_string(checked_.dt_ns) +
         " ns queued, taken from the next update on (" + std::to_string(steps_queued_) + " queued)";
}

bool StoneSimulation::step(UpdateResult& result, UpdateBudget& budget) {
  if (world_) return step_world(result, budget);
  const std::int64_t next_ns = clock_.next_time_ns();
  const std::int64_t auto_reset_ns = checked_.auto_reset_ns;
  const bool auto_reset = auto_reset_ns > 0 && next_ns - segment_start_ns_ >= auto_reset_ns;
  const MotionModel& model = checked_.setup.model;
  // A change that replaces the whole state (any pending one: all apply at this step) makes
  // integrating this step pointless, and lets a reset recover from a state the integrator
  // cannot handle.
  const bool replaced =
      auto_reset || std::any_of(pending_.begin(), pending_.end(),
                                [](const Change& change) { return change.replaces_state(); });
  // Everything below works on a copy and may throw; the simulation changes only at the end.
  RigidBodyState next = state_;
  if (!replaced) integrator_->advance(next, checked_.dt_s, flight_cache_);
  // Everything due at this step applies in order, each change announced with the state it
  // makes (segments of zero length at the same stamp, but every accepted request is seen).
  std::vector<Applied> applied = apply_changes(auto_reset, next);
  // The events carry the outputs of their states: checked before anything changes. Other
  // steps leave them to the end of update().
  for (Applied& a : applied) a.output = state_output(model, a.state);

  clock_.step();
  state_ = next;
  output_stale_ = applied.empty();
  if (!applied.empty()) output_ = applied.back().output;
  pending_.clear();
  if (!applied.empty())
    flight_cache_.invalidate();  // the integrator must not continue the old motion
  for (const Applied& a : applied) announce(a.reason, next_ns, a.state, a.output, result);
  return true;
}

}  // namespace virtual_go

namespace virtual_go {

// The changes due at this step (an auto reset, then the pending requests in order) applied to
// `next`; each with the state it makes (the last one's is `next`).
std::vector<StoneSimulation::Applied> StoneSimulation::apply_changes(bool auto_reset,
                                                                     RigidBodyState& next,
                                                                     std::size_t end) const {
  std::vector<Applied> applied;
  if (auto_reset) {
    next = checked_.initial_state;
    applied.push_back({EventReason::auto_reset, next, {}});
  }
  for (std::size_t k = 0; k < std::min(end, pending_.size()); ++k) {
    const Change& change = pending_[k];
    if (!change.initial_stone()) continue;  // apply_board_changes
    if (change.replaces_state()) {
      next = change.state;
    } else {
      const Eigen::Vector3d omega_world =
          change.frame == RequestFrame::body
              ? rotate_without_overflow(next.orientation, change.omega)
              : change.omega;
      next = with_angular_velocity_world(checked_.setup.model, next, omega_world);
    }
    applied.push_back({change.reason, next, {}});
  }
  return applied;
}

bool StoneSimulation::step_world(UpdateResult& result, UpdateBudget& budget) {
  const std::int64_t next_ns = clock_.next_time_ns();
  const bool auto_reset = auto_reset_due(next_ns);
  World& world = *world_;
  if (!mid_step_ && !held_ && !auto_reset && pending_.empty() && world.all_resting()) {
    // At rest with nothing due: no work, the state and its outputs stay bit for bit.
    clock_.step();
    return true;
  }
  planned_.valid = false;  // the World moves on and the queue empties
  const double t_s = seconds_between(epoch_ns_, next_ns);
  const MotionModel& model = checked_.setup.model;
  // Events up to t_s (the World moves on; if anything below throws, the state is held and the
  // World restarted by the replacement that ends the hold).
  if (!mid_step_) world_events_.clear();
  if (!held_) {
    // In slices of the World's own work units, asking the update's budget between them: one
    // step of hard contact can take far longer than a tick, and the node must keep answering.
    // The first slice is always taken, so every update makes progress.
    mid_step_ = true;
    while (!world.advance_to(t_s, world_events_, WorkBudget{kWorkPerSlice}).reached) {
      if (budget.spent()) return false;
    }
    mid_step_ = false;
  }
  std::vector<SegmentEvent> events;
  for (const WorldEvent& e : world_events_) events.push_back(segment_event(e));
  // The initial stone's changes due at this step, in order, as in step(), up to its removal
  // (the rest, and all of them while it is removed, apply one by one with the board changes).
  std::size_t batch_end = 0;
  if (!initial_removed_) {
    while (batch_end < pending_.size() && !removes_initial(pending_[batch_end])) ++batch_end;
  }
  RigidBodyState next = initial_removed_ ? state_ : held_ ? state_ : world.state(initial_id_);
  const std::vector<Applied> applied =
      initial_removed_ ? std::vector<Applied>{} : apply_changes(auto_reset, next, batch_end);
  if (!applied.empty()) {
    // One event per change, each with the state it makes; the World gets the last.
    std::vector<SegmentEvent> commands;
    for (const Applied& a : applied) {
      SegmentEvent command;
      command.stamp_ns = next_ns;
      command.reason = a.reason;
      command.stone = stone_name(0);
      command.state = a.state;
      command.output = state_output(model, a.state);
      commands.push_back(std::move(command));
    }
    world_events_.clear();
    if (held_) {
      // The World may have failed half-way: start it afresh from the replacement.
      reset_world(next, t_s);
      world.advance_to(t_s, world_events_);
    } else {
      world.set_state(initial_id_, next, t_s, world_events_);  // a resting stone wakes first
    }
    std::size_t i = 0;
    for (; i < world_events_.size() && world_events_[i].kind == WorldEventKind::wake; ++i) {
      events.push_back(segment_event(world_events_[i]));
    }
    for (SegmentEvent& command : commands) events.push_back(std::move(command));
    for (; i < world_events_.size(); ++i) events.push_back(segment_event(world_events_[i]));
  }
  apply_board_changes(t_s, next_ns, batch_end, events);
  const bool moved = !events.empty() || !world.all_resting();
  clock_.step();
  pending_.clear();
  commit_events(events, result);
  if (!initial_removed_) state_ = world.state(initial_id_);
  // Resting since before this step: the outputs already show this very state.
  if (moved) output_stale_ = true;
  return true;
}

}  // namespace virtual_go
