// What bag_report reads from a bag, as plain data (no ROS types), so the analysis can be unit
// tested without rosbag or a master. Times are integer nanoseconds, as in the message stamps.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/sim/segment_event.h"

namespace virtual_go {
namespace bag {

// The stamps of one topic (or of one tf frame pair), in the order the bag holds them.
struct TopicStamps {
  std::string topic;     // "/stone/odom", or "/tf world->stone" for one frame pair of /tf
  std::string datatype;  // "nav_msgs/Odometry"
  std::vector<std::int64_t> stamps_ns;
  bool header_stamps = true;  // false: no header, the bag's receipt time is used instead
  bool aperiodic = false;     // latched or event topics: no rate, period or gap figures
  bool at_node_rate = false;  // published by the node on every tick (~pose, ~odom, tf)
  // A stone of ~stones on /tf: every tick while it moves, once per simulated second at rest, so
  // no rate, period or gap figures (repeated and backwards stamps still count).
  bool on_change = false;
};

// virtual_go/StoneInfo, the part the physics check needs.
struct RecordingInfo {
  std::string topic;
  std::int64_t stamp_ns = 0;
  std::string world_frame = "world";
  std::string stone_frame = "stone";
  double mass = 0.0;                                                 // kg
  Eigen::Vector3d principal_moments_body = Eigen::Vector3d::Zero();  // kg m^2, body x, y, z
  std::string model;       // a motion model name (body/motion_model.h)
  std::string integrator;  // an integrator name (flight/integrator_registry.h)
  double dt_s = 0.0;
  std::int64_t dt_ns = 0;
  double rate_hz = 0.0;
  Eigen::Vector3d gravity_world = Eigen::Vector3d::Zero();  // m/s^2
  // The lens (m) and the board the contact checks need (docs/physics.md, "World").
  double width_m = 0.0;
  double height_m = 0.0;
  bool board_enabled = false;
  Eigen::Vector3d board_size_m = Eigen::Vector3d::Zero();  // x across, y along, z thickness
  // Contact laws: Jellett's integral holds in sustained contact only without rolling
  // resistance and spinning friction.
  double board_rolling_resistance_m = 0.0;
  double board_spinning_friction_m = 0.0;
  double table_rolling_resistance_m = 0.0;
  double table_spinning_friction_m = 0.0;
};

// One recorded state of a stone: a nav_msgs/Odometry (pose in the world, twist in the stone
// (body) frame), an entry of ~stones (its world twist rotated into the body frame when read) or a
// /tf transform (the pose only: has_twist false, velocities zero and unused).
struct OdomSample {
  std::int64_t stamp_ns = 0;
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation_raw = Eigen::Quaterniond::Identity();  // not normalised
  Eigen::Vector3d velocity_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_body = Eigen::Vector3d::Zero();
  bool has_twist = true;
};

// One stone named in ~stones (virtual_go/StoneStates), other than the one ~odom describes: its
// lens and mass from ~stones, its states from ~stones and from /tf (world -> its name), in stamp
// order (a /tf pose bitwise equal to a ~stones pose at the same stamp is kept once).
struct StoneTrack {
  std::string name;  // also its tf frame
  std::string color;
  double width_m = 0.0;
  double height_m = 0.0;
  double mass_kg = 0.0;
  std::vector<OdomSample> samples;
};

// One ~stones message: every stone's pose at one stamp (the overlap check's input).
struct StonesSnapshot {
  std::int64_t stamp_ns = 0;
  std::vector<std::size_t> track;  // index into Recording::stone_tracks, per stone
  std::vector<Eigen::Vector3d> position_world;
  std::vector<Eigen::Quaterniond> orientation_raw;
};

struct Recording {
  std::string path;
  std::size_t message_count = 0;
  double bag_duration_s = 0.0;  // receipt time, last - first
  std::vector<TopicStamps> topics;
  std::optional<RecordingInfo> info;
  std::string odom_topic;    // empty when none was found
  std::string events_topic;  // empty when none was found
  std::vector<OdomSample> odom;
  // One virtual_go/StoneEvent each, in bag order, read into the simulation's own event type
  // (sim/segment_event.h): the reason through its name table (a message with an unknown reason
  // is skipped and named in problems), state as the message carried it (world frame, the
  // quaternion not normalised, nothing checked), output left default.
  std::vector<SegmentEvent> events;
  // ~stones (virtual_go/StoneStates), when recorded: every stone it names, the initial stone
  // (~info's stone_frame) included; its samples are used only when the bag has no ~odom.
  std::string stones_topic;  // empty when none was found
  std::vector<StoneTrack> stone_tracks;
  std::vector<StonesSnapshot> snapshots;
  // What could not be read or found, one line each (a partial report says these).
  std::vector<std::string> problems;
};

}  // namespace bag
}  // namespace virtual_go
