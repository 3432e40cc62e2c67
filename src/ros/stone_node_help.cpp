#include "virtual_go/ros/stone_node.h"

namespace virtual_go {

const char* stone_node_help() {
  return R"(usage: rosrun virtual_go stone_node [__name:=stone] [_param:=value ...]
       roslaunch virtual_go stone.launch [rviz:=true] [record:=true] [bag:=FILE] [config:=YAML]
                                         [use_sim_time:=true]
       roslaunch virtual_go replay.launch [bag:=FILE] [rviz:=true]

Simulates a Go stone (a biconvex lens) as a rigid body on a timer on ROS time (use_sim_time
and /clock work; it warns when ROS time stands still for 3 s) with a fixed physics step, and
publishes its pose. SI units (REP 103). Needs a ROS master; --help does not.

Published (private names, ~ = the node's name, e.g. /stone):
  /tf                  world_frame -> stone_frame, stamped with the simulated time of the state
  ~pose                geometry_msgs/PoseStamped, world frame
  ~odom                nav_msgs/Odometry: pose in the world frame, twist in the stone frame
  ~marker              visualization_msgs/Marker (latched, every second): the lens as a
                       MESH_RESOURCE, an STL file in $ROS_HOME/virtual_go (~/.ros/virtual_go)
  ~info                virtual_go/StoneInfo (latched): stone, model, integrator, dt, initial state
  ~events              virtual_go/StoneEvent (latched): start of each motion segment (start,
                       reset, auto_reset, set_state, set_angular_velocity, time_jump)

Services (changes take effect at the next physics step, which starts a new segment):
  ~set_angular_velocity  virtual_go/SetAngularVelocity: angular_velocity rad/s, frame
                         "world" (default) or "stone"; rigid_body sets L = I w
  ~reset                 std_srvs/Trigger: back to the initial state (ROS time keeps running)
  ~set_state             virtual_go/SetState: pose and twist in the world frame

Parameters (defaults in brackets):
  ~rate                  publish rate, Hz, 0.001 to 10000 [60]
  ~dt                    physics step, s, a whole number of ns, >= 1e-6 [0.001]
  ~model                 constant_omega | rigid_body [rigid_body]
  ~integrator            euler | rk4 | splitting | exact [exact]
  ~gravity               [x, y, z] m/s^2, world frame [0, 0, -9.80665]
  ~stone/size            Japanese size number 22..40, sets the height [33 = 9.2 mm]
  ~stone/width           m [0.022]
  ~stone/height          m, overrides ~stone/size
  ~stone/material        slate | shell | glass | yunzi [slate]
  ~stone/density         kg/m^3, overrides the material
  ~stone/mass            kg, overrides density and material
  ~stone/color           black | white [black]
  ~initial/position      [x, y, z] m, world [0, 0, 0.05]
  ~initial/orientation   [x, y, z, w] body -> world, normalised [0, 0, 0, 1]
  ~initial/velocity      [x, y, z] m/s, world [0, 0, 0]
  ~initial/angular_velocity  [x, y, z] rad/s, world [0, 0, 0]
  ~max_angular_velocity  rad/s; larger requests are refused [500]
  ~auto_reset_period     s; reset when a segment is this old, 0 = never, else > ~dt [0]
  ~world_frame           [world]
  ~stone_frame           [stone]

Example (integers are fine for float64 fields; write exponents as 1.0e+9, since YAML reads
1e9 as a string, which rosservice refuses):
  rosservice call /stone/set_angular_velocity '{angular_velocity: {x: 0, y: 0, z: 30}, frame: world}'

Options:
  -h, --help             print this help and exit
)";
}

}  // namespace virtual_go
