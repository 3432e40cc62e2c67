// rviz's Publish Point tool on the board (/clicked_point), ROS-free: a click puts a stone at the
// Go point nearest to it, set down at rest through StoneSimulation::place (the ~place path, no
// second placement code), colours alternating black, white, black, ... A click that places
// nothing says why, naming the point, and does not flip the colour: off the board (more than
// half a spacing beyond the outer lines), onto a point where a stone already lies, or refused
// by place (no board, too many requests waiting).
#pragma once

#include <Eigen/Core>
#include <string>

#include "virtual_go/go/stone_color.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {

struct ClickOutcome {
  bool placed = false;
  std::string point;    // the nearest Go point ("A1" ... "T19"); "" off the board
  std::string name;     // the placed stone's name (its tf frame), when placed
  std::string message;  // what was placed, or why nothing was
};

class ClickPlacement {
 public:
  // position_world: the click in the world (board) frame, m; x and y choose the point (rviz
  // clicks on whatever surface is under the cursor, the board or a stone), z is ignored.
  // A stone lies at a point when the point is its nearest (as ~stones says: the initial stone,
  // a placed stone) or a placement there waits for the next physics step.
  ClickOutcome click(StoneSimulation& sim, const Eigen::Vector3d& position_world);
  // The colour of the next stone a click places: black first.
  StoneColor next_color() const { return next_; }

 private:
  StoneColor next_ = StoneColor::black;
};

}  // namespace virtual_go
