// StoneSimulation's requests (~reset, ~set_state, ~set_angular_velocity, ~place, ~remove,
// ~clear): each checked when asked (nothing changes if refused) and queued for the next physics
// step, which applies them (stone_simulation_step.cpp); and the answers they return.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {
namespace {

constexpr char kApplied[] = "applied at the next physics step";

}  // namespace

std::string StoneSimulation::reset() {
  Change change;
  change.reason = EventReason::reset;
  change.state = checked_.initial_state;
  enqueue(change);
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
  change.name = target;
  if (target.empty()) {
    change.state =
        state_from_request(fields, checked_.setup.model, position_world, orientation_xyzw,
                           velocity_world, angular_velocity_world, checked_.limits);
    check_clear_of_board("pose.position", change.state);
  } else {
    // A placed stone (or one waiting to be): its colour's body.
    StoneColor color = StoneColor::black;
    if (const PlacedStone* placed = placed_named(target)) {
      color = placed->color;
    } else if (const Change* waiting = place_waiting(target)) {
      color = waiting->color;
    }
    const WorldBodyModel& body = world_->body_model(world_->color_body(color));
    change.state = state_from_request(fields, body.setup().model, position_world, orientation_xyzw,
                                      velocity_world, angular_velocity_world, checked_.limits);
    check_clear_of_board("pose.position", change.state, &body.board());
  }
  enqueue(change);
  return answer();
}

std::string StoneSimulation::place(const PlaceRequest& request, std::string& answer_out) {
  require_board("~place");
  const StoneColor color = parse_stone_color(request.color);
  Change change;
  change.reason = EventReason::place;
  change.color = color;
  std::optional<SetDownPlan> set_down;  // a set-down's plan, checked for room
  if (!request.point.empty()) {
    if (!has_go_points(world_->config().board)) {
      throw InvalidArgument("point", "point: " + no_go_points_reason(world_->config().board) +
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
    if (change.sets_down()) set_down = check_room(world_->color_body(color), *change.point);
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
  if (names_a_stone(name_or_point)) {
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
  if (!has_go_points(world_->config().board)) return "";
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
  const bool was_here = names_a_stone(target);
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

void StoneSimulation::require_board(const std::string& request) const {
  if (!world_ || !world_->config().board_enabled) {
    throw RequestRefused("refused: " + request +
                         " needs the board (~board/enabled is false: there is only the stone '" +
                         stone_name(0) + "')");
  }
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

}  // namespace virtual_go
