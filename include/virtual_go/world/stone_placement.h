// Putting a stone of a colour at a Go point (docs/physics.md, "Placing stones"), either set down
// at rest or dropped. Physics, not rules: a point may be occupied (a drop onto a stone passes
// through it while stones do not interact, issue 15), captures are the caller's business.
//
// Set down: the stone lies flat (axis vertical, identity orientation) with its lowest point on
// the board's top face and velocities zero, and rests at once. Real stones are wider than the
// grid (black 22.2 mm on a 22.0 mm pitch), so it goes to
//   1. the horizontal position nearest its intersection at which it overlaps no stone, if one
//      lies within half a grid spacing (min(spacing_x, spacing_y) / 2) and its lowest point on
//      the top face; found exactly: the nearest point outside a union of discs is the point
//      itself, a radial projection onto one disc's circle, or an intersection of two circles;
//   2. otherwise the intersection itself, and the resting neighbours are nudged apart as a
//      player's stone pushes them: Gauss-Seidel projection of the pairwise non-overlap
//      constraints along the centre lines over the cluster of overlapping flat resting stones
//      (the new stone moving too; each overlapping pair moved apart by half the overlap each, a
//      stone that is not flat and resting on the top face never moves and takes nothing), sweep
//      after sweep until no pair overlaps. A sweep that finds a new overlap adds the stone to the
//      cluster. This approximates the minimal-displacement separation (alternating projections,
//      not its exact minimum). Moved stones stay resting at their new poses
//      (World::move_resting_stone); the result lists them.
// Overlap is judged on horizontal discs of radius half_width around each centre plus a margin
// of 1e-12 m, which bounds every lens from outside (a lens lies inside the ball of radius a about
// its centre), so a solved layout never overlaps in 3-D. Stones whose balls do not reach the new
// stone's height band are ignored.
//
// Dropped: flat, its lowest point drop_height_m above the top face, with the given velocity and
// angular velocity (zero by default); it then falls under the world's physics. No nudging.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone_color.h"
#include "virtual_go/world/world.h"

namespace virtual_go {

struct MovedStone {
  StoneId id;
  RigidBodyState state;   // its new pose, resting
  double displacement_m;  // horizontal distance moved
};

struct PlacementResult {
  StoneId id;             // the new stone
  RigidBodyState state;   // its state as placed (set down: at rest; dropped: at the release)
  double offset_m = 0.0;  // horizontal distance of its centre from the intersection
  bool nudged = false;    // true: no free pose within half a spacing, neighbours were pushed
  int sweeps = 0;         // relaxation sweeps (0 without nudging)
  std::vector<MovedStone> moved;  // resting stones the nudge moved, in id order
};

struct SetDownOptions {
  int max_sweeps = 100000;  // relaxation sweeps before giving up (> 0)
};

// Sets a stone of `color` down at `point` at t_s (>= world.time(); the world is advanced to t_s
// first, its events appended, then the new stone's rest event). Everything is checked before
// anything changes: InvalidArgument for a bad colour ("color"), a point off the grid ("point"),
// a world without a board or not of 19 lines ("board"), a bad time ("time"; also a t_s later
// than world.time() while a stone moves: the layout solved is the one at t_s, so advance the
// world there first), no room ("point": a nudge that would push a stone off the top face, or
// no convergence in max_sweeps). Only the colour's body may have been made (World::color_body).
PlacementResult set_down_stone(World& world, StoneColor color, GoPoint point, double t_s,
                               std::vector<WorldEvent>& events, const SetDownOptions& options = {});

// A stone as the set-down planner sees it: a horizontal disc at a height.
struct PlanStone {
  StoneId id;  // in the world (a stone only planned: any value, unused by the planner)
  Eigen::Vector2d centre_xy = Eigen::Vector2d::Zero();  // m, world
  double z_m = 0.0;                                     // centre height, world
  double half_width_m = 0.0;
  bool movable = false;  // flat and resting on the top face: a nudge may push it
};

// What set_down_stone would do, found without changing anything.
struct SetDownPlan {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // the new stone's centre
  double offset_m = 0.0;                         // from the intersection
  bool nudged = false;
  int sweeps = 0;
  // Stones the nudge moves: their index in the planner's list and new centre.
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> moves;
  PlanStone stone;  // the new stone (id unset)
};

// The world's stones as the planner sees them, in index order.
std::vector<PlanStone> plan_stones(const World& world);
// Plans a stone of `body` set down at `point` among `stones` (plan_stones of this world, or a
// layout the caller expects it to have). Throws InvalidArgument as set_down_stone ("point",
// "board", "max_sweeps"); changes nothing.
SetDownPlan plan_set_down(const World& world, std::size_t body, GoPoint point,
                          const std::vector<PlanStone>& stones, const SetDownOptions& options = {});
// The planner's layout after the plan: the moves made, the new stone appended.
void apply_plan(std::vector<PlanStone>& stones, const SetDownPlan& plan);

// Where drop_stone aims a stone of `body` at `point` among `stones` (as plan_set_down; the new
// stone not movable: it is in the air). Throws InvalidArgument "point" off the grid; changes
// nothing.
SetDownPlan plan_drop(const World& world, std::size_t body, GoPoint point,
                      const std::vector<PlanStone>& stones);

// Drops a stone of `color` over `point` from drop_height_m (>= 0, finite: "drop_height") with a
// twist (finite: "velocity", "angular_velocity"): flat, over the pose set_down_stone would take
// (the free spot nearest the intersection, else the resting neighbours nudged apart, as in
// `moved`; a nudge only when t_s is the world's time or all rest), or over the intersection
// itself when a stone covers it already or there is no room (it lands on what lies there). The
// other errors as set_down_stone, before anything changes.
PlacementResult drop_stone(World& world, StoneColor color, GoPoint point, double drop_height_m,
                           double t_s, std::vector<WorldEvent>& events,
                           const Eigen::Vector3d& velocity_world = Eigen::Vector3d::Zero(),
                           const Eigen::Vector3d& angular_velocity_world = Eigen::Vector3d::Zero());

}  // namespace virtual_go
