#include "virtual_go/ros/stone_node_help.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <vector>

#include "virtual_go/common/formatting.h"
#include "virtual_go/sim/segment_event.h"
#include "virtual_go/sim/stone_parameters.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {
namespace {

// The event reasons, wrapped below the ~events line.
std::string reason_lines() {
  constexpr std::size_t kIndent = 23, kWidth = 92;
  const std::vector<std::string> names = event_reason_names();
  std::string out;
  std::size_t column = kIndent + 8;  // after "reason: "
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string word = names[i] + (i + 1 < names.size() ? "," : "");
    if (i > 0 && column + 1 + word.size() > kWidth) {
      out += "\n" + std::string(kIndent, ' ');
      column = kIndent;
    } else if (i > 0) {
      out += " ";
      ++column;
    }
    out += word;
    column += word.size();
  }
  return out;
}

// One parameter: name (in a column name_width wide, the longest name's) and unit in columns,
// then the help and default wrapped at word boundaries to 100 columns (the default is never
// split).
std::string parameter_line(const ParameterInfo& p, std::size_t name_width) {
  constexpr std::size_t kUnitWidth = 7, kWidth = 100;
  const std::size_t indent = 2 + name_width + 1 + kUnitWidth + 1;
  std::vector<std::string> words;
  std::istringstream help(p.help);
  for (std::string word; help >> word;) words.push_back(word);
  if (!p.default_text.empty()) {
    words.back() += ";";
    words.push_back("default " + p.default_text);
  }
  std::ostringstream out;
  out << "  " << std::left << std::setw(static_cast<int>(name_width)) << "~" + p.name << " "
      << std::setw(static_cast<int>(kUnitWidth)) << p.unit << " ";
  std::size_t column = indent;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0 && column + 1 + words[i].size() > kWidth) {
      out << "\n" << std::string(indent, ' ');
      column = indent;
    } else if (i > 0) {
      out << " ";
      ++column;
    }
    out << words[i];
    column += words[i].size();
  }
  out << "\n";
  return out.str();
}

}  // namespace

std::string stone_node_help() {
  std::ostringstream out;
  out << R"(usage: rosrun virtual_go stone_node [__name:=stone] [_param:=value ...]
       roslaunch virtual_go stone.launch [rviz:=true] [record:=true] [bag:=FILE] [config:=YAML]
                                         [use_sim_time:=true]
       roslaunch virtual_go replay.launch [bag:=FILE] [rviz:=true]

Simulates a Go stone (a biconvex lens) as a rigid body on a timer on ROS time (use_sim_time
and /clock work; it warns when ROS time stands still for 3 s) with a fixed physics step, and
publishes its pose. With ~publish_clock it owns the time instead: it publishes /clock and runs
at ~real_time_factor times wall time (0: as fast as possible). SI units (REP 103). Needs a ROS
master; --help does not.

Published (private names, ~ = the node's name, e.g. /stone):
  /tf                  world_frame -> stone_frame, stamped with the simulated time of the state
  ~pose                geometry_msgs/PoseStamped, world frame
  ~odom                nav_msgs/Odometry: pose in the world frame, twist in the stone frame
  ~marker              visualization_msgs/Marker (latched, every second): the lens as a
                       MESH_RESOURCE, an STL file in $ROS_HOME/virtual_go (~/.ros/virtual_go)
  ~stone_markers       visualization_msgs/MarkerArray (latched, every second): every stone,
                       namespace its name, in its own frame; DELETE for a stone gone
  ~board_markers       visualization_msgs/MarkerArray (latched, every second; with
                       ~board/enabled): the board, the table, the lines and the star points
  ~info                virtual_go/StoneInfo (latched): stone, model, integrator, dt, initial
                       state, board and contact materials
  ~events              virtual_go/StoneEvent (latched): start of each motion segment, by
                       reason: )"
      << reason_lines() << R"(
                       (with ~board/enabled every change of contact regime); its exact
                       instant = header.stamp (rounded down to a ns) + time_offset;
                       stone (and other_stone of a stone-stone contact): the names
  ~stones              virtual_go/StoneStates (latched; at each event, and every tick while a
                       stone moves and someone listens): every stone's name, color, Go
                       point, size, mass, world pose and twist, resting
  /diagnostics         diagnostic_msgs/DiagnosticArray (every ~diagnostic_period, 1 s):
                       stones awake/resting, events per s, step cost, real-time factor,
                       pending requests, steps deferred, behind, paused, steps queued; WARN
                       while behind, ERROR while a failed step holds the state
  /clock               rosgraph_msgs/Clock (only with ~publish_clock): the simulated time of
                       each state published; starts at 1 s, stands while paused

Subscribed:
  clicked_point        geometry_msgs/PointStamped (rviz's Publish Point tool; another frame
                       than the world's through tf2): with the board, a stone set down at the
                       nearest Go point, black, white, black, ...; a click off the board or
                       onto a stone places nothing and warns

Services (changes take effect at the next physics step, which starts a new segment):
  ~set_angular_velocity  virtual_go/SetAngularVelocity: angular_velocity rad/s, frame
                         "world" (default) or "stone"; rigid_body sets L = I w; `name`: the
                         stone (empty: the initial stone `stone`)
  ~reset                 std_srvs/Trigger: the initial stone back to its initial state (also
                         after ~remove or ~clear took it off; ROS time keeps running)
  ~set_state             virtual_go/SetState: pose and twist in the world frame of stone
                         `name` (empty: `stone`); an unknown or removed name is refused
  ~place                 virtual_go/PlaceStone (with the board): a stone of `color` at Go
                         `point` ("A1".."T19"; set down at rest, or dropped from drop_height
                         m, 0 to )"
      << kMaxDropHeightM << R"() or at `pose`; answers its name
                         (black_1, white_1, ...: never reused; also its tf frame)
  ~remove                virtual_go/RemoveStone: a stone by name or by Go point
  ~clear                 std_srvs/Trigger: removes every stone, `stone` too (~reset puts it
                         back)
  ~pause                 std_srvs/Empty (as gazebo's pause_physics): no step is taken until
                         ~step or ~unpause; requests wait for the next step
  ~unpause               std_srvs/Empty: run again; following ROS time, the paused interval
                         is skipped (a time_jump event, detail "unpaused")
  ~step                  virtual_go/StepSimulation: while paused, take `ticks` steps of ~dt
                         (1 to )"
      << kMaxStepTicks << R"( queued)
  A request beyond the bounds below (~max_distance, ~max_speed, ~max_angular_velocity) is
  refused with the field, the value and the limit. So are requests beyond the )"
      << kMaxPendingRequests << R"( that
  may wait for a physics step (none comes while ROS time stands still), and
  ~set_angular_velocity while a failed step holds the state (~reset or ~set_state replace it).

Parameters (name, unit, meaning; default):
)";
  std::size_t name_width = 0;
  for (const ParameterInfo& p : stone_parameters()) {
    name_width = std::max(name_width, p.name.size() + 1);  // with the "~"
  }
  for (const ParameterInfo& p : stone_parameters()) out << parameter_line(p, name_width);
  out << R"(
Example (integers are fine for float64 fields; write exponents as 1.0e+9, since YAML reads
1e9 as a string, which rosservice refuses):
  rosservice call /stone/set_angular_velocity '{angular_velocity: {x: 0, y: 0, z: 30}, frame: world}'

Options:
  -h, --help             print this help and exit
)";
  return out.str();
}

}  // namespace virtual_go
