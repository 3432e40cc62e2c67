#include "virtual_go/ros/stone_node.h"

#include <rosgraph_msgs/Clock.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <stdexcept>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/ros/board_markers.h"
#include "virtual_go/ros/param_reader.h"
#include "virtual_go/ros/stone_markers.h"
#include "virtual_go/ros/stone_messages.h"
#include "virtual_go/sim/mesh_file.h"

namespace virtual_go {
namespace {

constexpr double kMarkerPeriodS = 1.0;                 // wall time between republished markers
constexpr std::int64_t kClockPatienceNs = 3000000000;  // ROS time still this long: say so
constexpr double kClockWatchPeriodS = 0.5;             // wall time between looks at the clock
constexpr double kBehindWarningPeriodS = 5.0;          // at most one "falls behind" warning
// How long a click in another frame waits for its transform (the node's thread waits with it;
// the first such click starts the tf listener, whose static transforms come latched at once).
constexpr double kClickTransformWaitS = 0.5;

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

Eigen::Vector3d to_eigen(const geometry_msgs::Vector3& v) {
  Eigen::Vector3d out;
  tf2::fromMsg(v, out);
  return out;
}

Eigen::Vector3d to_eigen(const geometry_msgs::Point& p) {
  Eigen::Vector3d out;
  tf2::fromMsg(p, out);
  return out;
}

Eigen::Vector4d to_xyzw(const geometry_msgs::Quaternion& q) {
  return Eigen::Vector4d(q.x, q.y, q.z, q.w);
}

// Runs a request; a refusal becomes success false with the reason, the state untouched. The
// reasons quote user strings cut short (quote_user_text), so neither the answer nor the log
// line grows with the request.
template <class Response, class Request>
void answer(const char* service, const Request& request, Response& response) {
  try {
    response.message = request();
    response.success = true;
  } catch (const std::exception& e) {  // InvalidArgument (a field), RequestRefused, any other
    response.success = false;
    response.message = e.what();
    ROS_WARN("stone_node: %s refused: %s", service, e.what());
  }
}

// Where ROS keeps its files: $ROS_HOME, else ~/.ros (rospkg's rule); "" when neither is known.
std::string mesh_folder() {
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home && *ros_home) return std::string(ros_home) + "/virtual_go";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::string(home) + "/.ros/virtual_go";
  return "";
}

// The MESH_RESOURCE marker and its STL file; the TRIANGLE_LIST when the file cannot be written.
visualization_msgs::Marker make_marker(const StoneSimulation& sim) {
  const StoneConfig& c = sim.config();
  try {
    const std::string folder = mesh_folder();
    if (folder.empty()) throw std::runtime_error("neither ROS_HOME nor HOME is set");
    const std::string stl = binary_stl(stone_display_mesh(sim.stone()));
    const std::string path = write_mesh_file(folder, mesh_file_name(sim.stone().shape, stl), stl);
    return to_mesh_marker_msg("file://" + path, c.color, c.stone_frame);
  } catch (const std::exception& e) {
    visualization_msgs::Marker marker = to_marker_msg(sim.stone(), c.color, c.stone_frame);
    ROS_WARN(
        "stone_node: no mesh file for ~marker (%s); publishing the lens as a TRIANGLE_LIST "
        "instead: %u bytes every %g s",
        e.what(), ros::serialization::serializationLength(marker), kMarkerPeriodS);
    return marker;
  }
}

StoneConfig read_config(const ros::NodeHandle& private_nh) {
  for (const std::string& name : unknown_parameters(private_nh)) {
    ROS_WARN("ignoring unknown parameter ~%s (see stone_node --help)", cut_user_text(name).c_str());
  }
  return read_stone_config(private_nh);
}

}  // namespace

StoneNode::StoneNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : nh_(nh),
      private_nh_(private_nh),
      sim_(read_config(private_nh)),
      clock_watch_(kClockPatienceNs),
      update_stats_(steady_ns()),
      diagnostics_(nh, private_nh) {
  const StoneConfig& c = sim_.config();
  if (c.rate_hz * c.dt_s > 1.0) {
    ROS_WARN(
        "~rate %g Hz is faster than the physics step ~dt %g s: ticks without a new step "
        "publish nothing",
        c.rate_hz, c.dt_s);
  }
  pose_pub_ = private_nh_.advertise<geometry_msgs::PoseStamped>("pose", 10);
  odom_pub_ = private_nh_.advertise<nav_msgs::Odometry>("odom", 10);
  // Latched: late subscribers (rviz, rosbag record, tools) still get the shape, the
  // configuration and the latest segment start.
  marker_pub_ = private_nh_.advertise<visualization_msgs::Marker>("marker", 1, true);
  info_pub_ = private_nh_.advertise<StoneInfo>("info", 1, true);
  // Every accepted request is its own event, and a burst of 100 calls lands within a few
  // ticks: a queue of 10 dropped 355 of 1,567 events in the service fuzz (scripts/service_fuzz.py).
  events_pub_ = private_nh_.advertise<StoneEvent>("events", 1000, true);
  // Every stone's state as gazebo's model_states: latched, so a late subscriber gets the last
  // change (every stone at rest after a rest event); while a stone moves, every tick that has
  // a subscriber (stone_states_due).
  stones_pub_ = private_nh_.advertise<StoneStates>("stones", 10, true);
  // rviz drops a marker for good when it gets it before the first transform of the marker's
  // frame: tf2's message filter holds it, and once the frame appears tf2 fails every pending
  // request stamped more than its cache time (10 s) before the frame's latest data, which a
  // stamp of 0 always is (BufferCore::testTransformableRequests; ros-visualization/rviz#494).
  // Which arrives first depends on start order and on two separate connections, so no single
  // message may matter: the marker is republished every kMarkerPeriodS, and a dropped one is
  // replaced by the next. A TRIANGLE_LIST of the lens is 138 KB per message, so the marker is
  // a MESH_RESOURCE naming a binary STL of the lens written here (233 bytes with the default
  // ROS_HOME: 0.23 KB/s). Rejected: a marker in the fixed frame (it must carry the pose at
  // every tick, duplicating /tf) and a robot model (rviz reads robot_description once, so it
  // depends on start order too). The first one goes out right after the first transform.
  marker_ = make_marker(sim_);
  // The initial stone's marker is the prototype of its colour; the other colour's (placed
  // stones) is the same mesh recoloured as to_marker_msg colours it. Its lens is the initial
  // stone's, not the colour's body (black 22.2 mm, white 21.9 mm): a 0.3 mm difference in rviz.
  stone_prototypes_[c.color] = marker_;
  for (const std::string& color : stone_color_names()) {
    if (stone_prototypes_.count(color)) continue;
    visualization_msgs::Marker other = marker_;
    other.color = to_marker_msg(sim_.stone(), color, c.stone_frame).color;
    stone_prototypes_[color] = other;
  }
  stone_markers_pub_ =
      private_nh_.advertise<visualization_msgs::MarkerArray>("stone_markers", 1, true);
  // The board is drawn in the fixed frame: it needs no transform, but rviz's tf filter still
  // holds it until the frame exists and can drop it as above, so it goes out with the marker.
  if (const std::optional<WorldConfig>& world = sim_.world_config()) {
    board_markers_ = to_board_markers_msg(make_board_drawing(world->board), c.world_frame);
    board_markers_pub_ =
        private_nh_.advertise<visualization_msgs::MarkerArray>("board_markers", 1, true);
  }
  marker_timer_ =
      nh_.createWallTimer(ros::WallDuration(kMarkerPeriodS), &StoneNode::on_marker_timer, this);
  if (ros::Time::isSimTime() && !c.publish_clock) {  // with it, its own /clock: no waiting
    clock_watch_timer_ = nh_.createWallTimer(ros::WallDuration(kClockWatchPeriodS),
                                             &StoneNode::on_clock_watch, this);
  }

  set_angular_velocity_srv_ = private_nh_.advertiseService(
      "set_angular_velocity", &StoneNode::on_set_angular_velocity, this);
  reset_srv_ = private_nh_.advertiseService("reset", &StoneNode::on_reset, this);
  set_state_srv_ = private_nh_.advertiseService("set_state", &StoneNode::on_set_state, this);
  // Stones on the board (with ~board/enabled; otherwise they answer why not).
  place_srv_ = private_nh_.advertiseService("place", &StoneNode::on_place, this);
  remove_srv_ = private_nh_.advertiseService("remove", &StoneNode::on_remove, this);
  clear_srv_ = private_nh_.advertiseService("clear", &StoneNode::on_clear, this);

  diagnostics_.setHardwareID(ros::this_node::getName());
  diagnostics_.add("simulation", this, &StoneNode::fill_diagnostics);

  // The simulation controls take std_srvs/Empty as gazebo's /gazebo/pause_physics and
  // /gazebo/unpause_physics do, so a gazebo user's habits and scripts carry over; the answer
  // goes to the log. ~step has no gazebo service to follow: it says how many ticks it queued.
  pause_srv_ = private_nh_.advertiseService("pause", &StoneNode::on_pause, this);
  unpause_srv_ = private_nh_.advertiseService("unpause", &StoneNode::on_unpause, this);
  step_srv_ = private_nh_.advertiseService("step", &StoneNode::on_step, this);
  // rviz's Publish Point tool publishes on /clicked_point, in its fixed frame.
  clicked_point_sub_ = nh_.subscribe("clicked_point", 10, &StoneNode::on_clicked_point, this);

  if (c.publish_clock) {
    // The node owns the time: a timer on ROS time would wait for the /clock it publishes
    // itself (under use_sim_time), so it runs on wall time. At factor 0 the ticks follow each
    // other (period = one update's allowance): as fast as possible, and services and SIGINT are
    // served between ticks.
    pacer_.emplace(c.rate_hz, c.real_time_factor);
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    const double period_s = c.real_time_factor > 0.0
                                ? 1.0 / c.rate_hz
                                : 1e-9 * static_cast<double>(update_allowance(c.rate_hz).count());
    own_clock_timer_ =
        nh_.createWallTimer(ros::WallDuration(period_s), &StoneNode::on_own_clock_timer, this);
  } else {
    // On ROS time, so use_sim_time and /clock drive it too.
    timer_ = nh_.createTimer(ros::Duration(1.0 / c.rate_hz), &StoneNode::on_timer, this);
  }
  ROS_INFO("stone_node: %s model, %s integrator, dt %lld ns, %g Hz, frames %s -> %s",
           c.model.c_str(), c.integrator.c_str(), static_cast<long long>(sim_.dt_ns()), c.rate_hz,
           c.world_frame.c_str(), c.stone_frame.c_str());
}

void StoneNode::on_timer(const ros::TimerEvent&) {
  // update() never throws; a failure comes back once in result.error, with its cause. It works
  // at most half a tick (update_allowance) plus one step, so services and timers keep being
  // served however slow the physics is.
  const std::int64_t now_ns = static_cast<std::int64_t>(ros::Time::now().toNSec());
  DeadlineBudget budget(update_allowance(sim_.config().rate_hz));
  const std::int64_t update_start_ns = steady_ns();
  const UpdateResult result = sim_.update(now_ns, budget);
  update_stats_.record(steady_ns() - update_start_ns, result, sim_.time_ns());
  if (result.steps_deferred > 0) {
    ROS_WARN_THROTTLE(kBehindWarningPeriodS,
                      "stone_node: the physics falls behind ROS time: %.3f s behind after a tick's "
                      "%.1f ms of work (%lld steps left for the next tick); topics and services "
                      "go on, and past %.1f s behind the stone skips ahead (a time_jump event)",
                      to_seconds(result.behind_ns),
                      1e-6 * static_cast<double>(update_allowance(sim_.config().rate_hz).count()),
                      static_cast<long long>(result.steps_deferred), to_seconds(sim_.max_lag_ns()));
  }
  publish_result(result);
  diagnostics_.update();  // publishes once per ~diagnostic_period (1 s) of ROS time
}

void StoneNode::on_own_clock_timer(const ros::WallTimerEvent&) {
  DeadlineBudget budget(update_allowance(sim_.config().rate_hz));
  std::int64_t mark_ns = steady_ns();
  bool clock_sent = false;
  pacer_->tick(sim_, mark_ns, budget, [&](const UpdateResult& result) {
    // Owning the clock, nothing can fall behind: steps a budget left are the pace slowing down,
    // not a lag to warn about (diagnostics show the real-time factor reached).
    UpdateResult own = result;
    own.steps_deferred = 0;
    own.behind_ns = 0;
    update_stats_.record(steady_ns() - mark_ns, own, sim_.time_ns());
    publish_result(own);
    if (result.advanced) {
      // /clock at the state just published: tf lookups at "now" find it exactly.
      rosgraph_msgs::Clock clock;
      clock.clock = to_ros_time(result.stamp_ns);
      clock_pub_.publish(clock);
      clock_sent = true;
    }
    mark_ns = steady_ns();
  });
  if (!clock_sent && sim_.started()) {
    // Paused (or held): the time stands, and a late subscriber still learns it.
    rosgraph_msgs::Clock clock;
    clock.clock = to_ros_time(sim_.time_ns());
    clock_pub_.publish(clock);
  }
  diagnostics_.update();
}

void StoneNode::publish_result(const UpdateResult& result) {
  if (!result.error.empty()) {
    ROS_ERROR(
        "stone_node: %s; the state is held and nothing is published until ~reset or "
        "~set_state",
        result.error.c_str());
  }
  try {
    for (const SegmentEvent& event : result.events) {
      if (event.reason == EventReason::time_jump && event.detail == "physics_behind") {
        ROS_WARN_THROTTLE(
            kBehindWarningPeriodS,
            "stone_node: the physics fell more than %.1f s behind ROS time; the stone "
            "skips ahead to %.9f s and continues from its state",
            to_seconds(sim_.max_lag_ns()), to_seconds(event.stamp_ns));
      } else if (event.reason == EventReason::time_jump && event.detail == "unpaused") {
        ROS_INFO(
            "stone_node: unpaused; the stone continues from its paused state at ROS time "
            "%.9f s (a time_jump event: the paused interval is not simulated)",
            to_seconds(event.stamp_ns));
      } else if (event.reason == EventReason::time_jump) {
        ROS_WARN("stone_node: ROS time jumped to %.9f s; the stone continues from there",
                 to_seconds(event.stamp_ns));
      }
      if (event.reason == EventReason::start) info_pub_.publish(to_info_msg(sim_));
    }
    publish_events(result);
    // Only a state that advanced is published: each stamp appears once (no TF_REPEATED_DATA).
    if (result.advanced) publish_state(result.stamp_ns);
    const bool all_resting = sim_.world() ? sim_.world()->all_resting() : sim_.resting();
    if (stone_states_due(result, all_resting, stones_pub_.getNumSubscribers() > 0)) {
      stones_pub_.publish(to_stone_states_msg(stone_states(sim_), to_ros_time(result.stamp_ns),
                                              sim_.config().world_frame));
    }
    // Stones came or went: their markers now, not at the next marker tick.
    const bool stones_changed =
        std::any_of(result.events.begin(), result.events.end(), [](const SegmentEvent& e) {
          return e.reason == EventReason::place || e.reason == EventReason::remove ||
                 e.reason == EventReason::clear;
        });
    if (stones_changed && marker_sent_) publish_stone_markers();
    if (result.advanced && !marker_sent_) {
      marker_pub_.publish(marker_);
      publish_stone_markers();
      if (board_markers_pub_) board_markers_pub_.publish(board_markers_);
      marker_sent_ = true;
    }
  } catch (const std::exception& e) {
    // Publishing (ROS serialisation, a broken connection) must not end the node either.
    ROS_ERROR_THROTTLE(10.0, "stone_node: publishing failed: %s", e.what());
  }
}

void StoneNode::fill_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const DiagnosticReport report = diagnostic_report(sim_, update_stats_.take(steady_ns()));
  status.summary(static_cast<unsigned char>(report.level), report.message);
  for (const auto& [key, value] : report.values) status.add(key, value);
}

void StoneNode::publish_stone_markers() {
  std::vector<StoneMarker> stones;
  geometry_msgs::Pose identity;
  identity.orientation.w = 1.0;
  // Each stone in its own frame (its name), moved by /tf.
  for (const StoneStateEntry& s : stone_states(sim_)) {
    stones.push_back({s.name, s.color, s.name, identity});
  }
  stone_markers_pub_.publish(to_stone_markers_msg(stones, drawn_stones_, stone_prototypes_));
  drawn_stones_.clear();
  for (const StoneMarker& s : stones) drawn_stones_.push_back(s.name);
}

void StoneNode::on_marker_timer(const ros::WallTimerEvent&) {
  if (marker_sent_) marker_pub_.publish(marker_);
  if (marker_sent_) publish_stone_markers();
  if (marker_sent_ && board_markers_pub_) board_markers_pub_.publish(board_markers_);
}

void StoneNode::on_clock_watch(const ros::WallTimerEvent&) {
  const std::int64_t wall_ns = steady_ns();
  const std::int64_t ros_ns = static_cast<std::int64_t>(ros::Time::now().toNSec());
  const double patience_s = to_seconds(clock_watch_.patience_ns());
  switch (clock_watch_.observe(wall_ns, ros_ns)) {
    case ClockWatch::Change::stalled:
      if (ros_ns == 0) {
        ROS_WARN(
            "stone_node: waiting for /clock: use_sim_time is true and no /clock has arrived "
            "for %g s, so nothing moves or is published. Play a bag with --clock or start a "
            "simulator; for a live run set use_sim_time false (stone.launch does, unless "
            "use_sim_time:=true)",
            patience_s);
      } else {
        ROS_WARN(
            "stone_node: waiting for /clock: ROS time (use_sim_time) has stood at %.3f s for "
            "%g s, so nothing moves or is published until /clock moves on",
            to_seconds(ros_ns), patience_s);
      }
      break;
    case ClockWatch::Change::resumed:
      ROS_INFO("stone_node: /clock moves again");
      break;
    case ClockWatch::Change::none:
      break;
  }
}

void StoneNode::publish_events(const UpdateResult& result) {
  for (const SegmentEvent& event : result.events) {
    events_pub_.publish(to_event_msg(event, sim_.config().world_frame));
  }
}

void StoneNode::publish_state(std::int64_t stamp_ns) {
  const StoneConfig& c = sim_.config();
  const StateOutput& output = sim_.output();
  const ros::Time stamp = to_ros_time(stamp_ns);
  // One TFMessage per tick: the initial stone, every placed stone that moves, and each resting
  // placed stone once when it comes to rest and then every kRestingTfPeriodNs of simulated time
  // (well inside tf's 10 s cache, so rviz and tf_echo keep finding it) rather than every tick.
  // The initial stone while it is there (~remove and ~clear take it off, ~reset puts it back).
  std::vector<geometry_msgs::TransformStamped> transforms;
  if (sim_.initial_present()) {
    transforms.push_back(to_transform_msg(output, stamp, c.world_frame, c.stone_frame));
  }
  // Kept in step with the placed stones by id (entry k: stone k), without a map rebuilt per
  // tick: with 360 resting stones that per-tick work was a third of the node's CPU.
  const std::vector<PlacedStone>& placed = sim_.placed_stones();
  bool same = tf_sent_ns_.size() == placed.size();
  for (std::size_t k = 0; same && k < placed.size(); ++k)
    same = tf_sent_ns_[k].first == placed[k].id;
  if (!same) {
    std::vector<std::pair<StoneId, std::int64_t>> kept;  // removed stones are forgotten
    for (const PlacedStone& p : placed) {
      const auto it = std::find_if(tf_sent_ns_.begin(), tf_sent_ns_.end(),
                                   [&](const auto& e) { return e.first == p.id; });
      kept.emplace_back(p.id, it == tf_sent_ns_.end() ? -1 : it->second);
    }
    tf_sent_ns_ = std::move(kept);
  }
  for (std::size_t k = 0; k < placed.size(); ++k) {
    const PlacedStone& p = placed[k];
    const World& world = *sim_.world();
    std::int64_t& last = tf_sent_ns_[k].second;
    const bool due = last < 0 || stamp_ns - last >= kRestingTfPeriodNs || last > stamp_ns ||
                     !world.is_resting(p.id);
    if (!due) continue;
    const WorldBody& body = world.body_model(world.body_of(p.id)).body();
    transforms.push_back(to_transform_msg(state_output(body.model, world.state(p.id)), stamp,
                                          c.world_frame, p.name));
    last = stamp_ns;
  }
  if (!transforms.empty()) tf_broadcaster_.sendTransform(transforms);
  if (!sim_.initial_present()) return;  // ~pose and ~odom are the initial stone's
  if (pose_pub_.getNumSubscribers() > 0) {
    pose_pub_.publish(to_pose_stamped_msg(output, stamp, c.world_frame));
  }
  if (odom_pub_.getNumSubscribers() > 0) {
    odom_pub_.publish(to_odometry_msg(output, stamp, c.world_frame, c.stone_frame));
  }
}

bool StoneNode::on_set_angular_velocity(SetAngularVelocity::Request& request,
                                        SetAngularVelocity::Response& response) {
  answer(
      "set_angular_velocity",
      [&] {
        return sim_.set_angular_velocity(to_eigen(request.angular_velocity), request.frame,
                                         request.name);
      },
      response);
  return true;
}

bool StoneNode::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  answer(
      "reset", [&] { return sim_.reset(); }, response);
  return true;
}

bool StoneNode::on_place(PlaceStone::Request& request, PlaceStone::Response& response) {
  answer(
      "place",
      [&] {
        PlaceRequest r;
        r.point = request.point;
        r.color = request.color;
        r.position_world = to_eigen(request.pose.position);
        r.orientation_xyzw = to_xyzw(request.pose.orientation);
        r.drop_height_m = request.drop_height;
        r.velocity_world = to_eigen(request.twist.linear);
        r.angular_velocity_world = to_eigen(request.twist.angular);
        std::string message;
        response.name = sim_.place(r, message);
        return response.name + ": " + message;
      },
      response);
  return true;
}

bool StoneNode::on_remove(RemoveStone::Request& request, RemoveStone::Response& response) {
  answer(
      "remove",
      [&] {
        std::string message;
        const std::string name = sim_.remove(request.name, message);
        return name + ": " + message;
      },
      response);
  return true;
}

bool StoneNode::on_clear(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  answer(
      "clear", [&] { return sim_.clear(); }, response);
  return true;
}

bool StoneNode::on_pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ROS_INFO("stone_node: ~pause: %s", sim_.pause().c_str());
  return true;
}

bool StoneNode::on_unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ROS_INFO("stone_node: ~unpause: %s", sim_.unpause().c_str());
  return true;
}

bool StoneNode::on_step(StepSimulation::Request& request, StepSimulation::Response& response) {
  answer(
      "step", [&] { return sim_.step(request.ticks); }, response);
  return true;
}

void StoneNode::on_clicked_point(const geometry_msgs::PointStamped::ConstPtr& message) {
  const std::string& world_frame = sim_.config().world_frame;
  Eigen::Vector3d position_world = to_eigen(message->point);
  const std::string& frame = message->header.frame_id;
  if (!frame.empty() && frame != world_frame && frame != "/" + world_frame) {
    if (!tf_buffer_) {
      tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
      tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
    }
    try {
      // The latest transform: a click marks a place on the board, which does not move.
      const geometry_msgs::TransformStamped t = tf_buffer_->lookupTransform(
          world_frame, frame, ros::Time(0), ros::Duration(kClickTransformWaitS));
      position_world = tf2::transformToEigen(t) * position_world;
    } catch (const tf2::TransformException& e) {
      ROS_WARN("stone_node: clicked_point in frame %s places nothing: no transform to %s (%s)",
               cut_user_text(frame).c_str(), world_frame.c_str(), e.what());
      return;
    }
  }
  const ClickOutcome out = clicks_.click(sim_, position_world);
  if (out.placed) {
    ROS_INFO("stone_node: clicked_point: %s", out.message.c_str());
  } else {
    ROS_WARN("stone_node: clicked_point: %s", out.message.c_str());
  }
}

bool StoneNode::on_set_state(SetState::Request& request, SetState::Response& response) {
  answer(
      "set_state",
      [&] {
        return sim_.set_state(to_eigen(request.pose.position), to_xyzw(request.pose.orientation),
                              to_eigen(request.twist.linear), to_eigen(request.twist.angular),
                              request.name);
      },
      response);
  return true;
}

}  // namespace virtual_go
