// The ROS adapter around StoneSimulation: parameters in, a timer on ROS time (or, with
// ~publish_clock, a wall timer and /clock out), tf2 and topics out, services in.
// Single-threaded: construct, then ros::spin().
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PointStamped.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/PlaceStone.h"
#include "virtual_go/RemoveStone.h"
#include "virtual_go/SetAngularVelocity.h"
#include "virtual_go/SetState.h"
#include "virtual_go/StepSimulation.h"
#include "virtual_go/sim/click_placement.h"
#include "virtual_go/sim/clock_watch.h"
#include "virtual_go/sim/sim_diagnostics.h"
#include "virtual_go/sim/sim_pacer.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

class StoneNode {
 public:
  // Reads ~ parameters; throws ConfigError naming the bad parameter.
  StoneNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

 private:
  void on_timer(const ros::TimerEvent& event);
  // With ~publish_clock: the simulation's own pace, on wall time.
  void on_own_clock_timer(const ros::WallTimerEvent& event);
  // Logs and publishes what an update returned (events, the state, the marker once).
  void publish_result(const UpdateResult& result);
  void publish_state(std::int64_t stamp_ns);
  void publish_events(const UpdateResult& result);
  void on_marker_timer(const ros::WallTimerEvent& event);
  void on_clock_watch(const ros::WallTimerEvent& event);
  void fill_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& status);

  bool on_set_angular_velocity(SetAngularVelocity::Request& request,
                               SetAngularVelocity::Response& response);
  bool on_reset(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool on_set_state(SetState::Request& request, SetState::Response& response);
  bool on_place(PlaceStone::Request& request, PlaceStone::Response& response);
  bool on_remove(RemoveStone::Request& request, RemoveStone::Response& response);
  bool on_clear(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool on_pause(std_srvs::Empty::Request& request, std_srvs::Empty::Response& response);
  bool on_unpause(std_srvs::Empty::Request& request, std_srvs::Empty::Response& response);
  bool on_step(StepSimulation::Request& request, StepSimulation::Response& response);
  // rviz's Publish Point tool: a stone set down at the nearest Go point (sim/click_placement.h).
  void on_clicked_point(const geometry_msgs::PointStamped::ConstPtr& message);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  StoneSimulation sim_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Publisher pose_pub_;
  ros::Publisher odom_pub_;
  ros::Publisher marker_pub_;
  ros::Publisher info_pub_;
  ros::Publisher events_pub_;
  ros::Publisher stones_pub_;  // ~stones, latched (sim/stone_states.h says when)
  ros::ServiceServer set_angular_velocity_srv_;
  ros::ServiceServer reset_srv_;
  ros::ServiceServer set_state_srv_;
  ros::ServiceServer place_srv_;
  ros::ServiceServer remove_srv_;
  ros::ServiceServer clear_srv_;
  // The simulated time each placed stone's transform last went out (resting ones are re-sent
  // every kRestingTfPeriodNs, not every tick), in placement order (-1: not yet).
  static constexpr std::int64_t kRestingTfPeriodNs = 1000000000;
  std::vector<std::pair<StoneId, std::int64_t>> tf_sent_ns_;
  ros::ServiceServer pause_srv_;
  ros::ServiceServer unpause_srv_;
  ros::ServiceServer step_srv_;
  // clicked_point (rviz's Publish Point, /clicked_point): the colours alternate per node. A
  // click in another frame than the world's is transformed with tf2; the listener is made at
  // the first such click only, so the node does not read its own /tf otherwise.
  ros::Subscriber clicked_point_sub_;
  ClickPlacement clicks_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  ros::Timer timer_;
  // With ~publish_clock: the pace of the simulation, its wall timer and /clock.
  std::optional<SimPacer> pacer_;
  ros::WallTimer own_clock_timer_;
  ros::Publisher clock_pub_;
  // The marker, built once; republished every second once tf of the stone flows (see
  // stone_node.cpp, StoneNode::StoneNode, for why).
  visualization_msgs::Marker marker_;
  bool marker_sent_ = false;
  ros::WallTimer marker_timer_;
  // Every stone as one MarkerArray (~stone_markers, latched; ros/stone_markers.h), sent and
  // republished with ~marker for the same reason. The prototypes: a marker per stone colour.
  ros::Publisher stone_markers_pub_;
  std::map<std::string, visualization_msgs::Marker> stone_prototypes_;
  std::vector<std::string> drawn_stones_;  // names in the last array: deleted when gone
  void publish_stone_markers();
  // With ~board/enabled: the board's markers (~board_markers, latched, world frame), sent and
  // republished with the stone's marker, for the same reason.
  ros::Publisher board_markers_pub_;
  visualization_msgs::MarkerArray board_markers_;
  // Under use_sim_time: says so when ROS time stands still (no /clock).
  ClockWatch clock_watch_;
  ros::WallTimer clock_watch_timer_;
  // /diagnostics: one status, from the updates' costs (UpdateStats) and the simulation.
  UpdateStats update_stats_;
  diagnostic_updater::Updater diagnostics_;
};

}  // namespace virtual_go
