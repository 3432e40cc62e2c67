// What ~stones (virtual_go/StoneStates) says of every stone, ROS-free: one entry per stone, as
// gazebo's model_states gives one per model. The node copies the entries into the message's
// parallel arrays (ros/stone_messages.h).
//
// When it goes out (stone_states_due): latched, at every update with an event (a change from
// outside, a change of contact regime, rest, wake) and, while some stone moves, at every new
// state as long as someone listens. So the latched message is the latest change (a late
// subscriber gets every stone at rest after a rest event), and resting stones cost nothing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/sim/state_output.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

struct StoneStateEntry {
  std::string name;   // the stone's name, also its tf frame
  std::string color;  // "black" | "white"
  std::string point;  // nearest Go point "A1" ... "T19"; "" off the grid or without a 19-line board
  double width_m = 0.0;
  double height_m = 0.0;
  double mass_kg = 0.0;
  StateOutput output;    // world frame, at the centre of mass (checked finite)
  bool resting = false;  // velocities exactly zero, the state frozen bit for bit
};

// Every stone of the simulation: the initial stone (named by ~stone_frame, ~stone/color, with the
// board's Go point), then the placed stones in placement order. Valid after an update that
// advanced.
std::vector<StoneStateEntry> stone_states(const StoneSimulation& sim);

// Whether ~stones goes out after this update (see above): `listened` when it has subscribers.
bool stone_states_due(const UpdateResult& result, bool all_resting, bool listened);

}  // namespace virtual_go
