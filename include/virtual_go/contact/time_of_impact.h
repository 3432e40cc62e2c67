// The exact time of a flying stone's first contact with the board or the table (docs/physics.md,
// "Time of impact"). The flight is the closed form (ExactMotion) from an anchor state; the search
// never steps through a contact: each step is a conservative-advancement step (FlightGapBound,
// the largest safe step over the board's separating axes, the smallest over board and table),
// and near the contact the same steps become Newton steps on a lower model of the gap, which
// approach the root from the contact-free side with quadratic convergence. The returned time is
// therefore never after the first contact, and the gap there is zero to round-off. The flight is
// not changed: this is a query.
#pragma once

#include "virtual_go/go/board_distance.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

struct TimeOfImpactOptions {
  // Below this gap (m) steps count as polishing rather than advancement.
  double polish_gap_m = 1e-9;
  // A stone closer than this (m), or overlapping by less, and separating counts as touching:
  // the search lets it leave (a stone that has just bounced) instead of reporting a contact.
  double touch_tolerance_m = 1e-9;
  // Safety net against a pathological grazing approach; the search then stops early and says
  // so (`exhausted`), having proven the flight contact-free up to `time_s`.
  int max_steps = 100000;
};

struct TimeOfImpact {
  bool hit = false;        // a contact at time_s; false: none before the horizon (or exhausted)
  bool exhausted = false;  // max_steps reached: contact-free up to time_s, search again from there
  double time_s = 0.0;     // the contact time, else the horizon (or how far the search got), s
  RigidBodyState state;    // the flight's state at time_s
  BoardContact contact;    // nearest feature at time_s: gap (~0 at a hit), witness, normal
  // -(n . u_P) at time_s, m/s: > 0 approaching. A hit with a speed <= 0 at the start time means
  // the stone was not in flight there: resting on the board (speed 0) or already overlapping by
  // more than the touch tolerance.
  double approach_speed_mps = 0.0;
  int advancement_steps = 0;  // steps taken with the gap above polish_gap_m
  int polish_steps = 0;       // steps taken below it
};

// First contact of the flight that passes through `anchor` at `anchor_time_s` (world time line,
// s) with the board or the table, searched from `start_time_s` up to `horizon_s`
// (all finite, start_time_s <= horizon_s). Throws InvalidArgument naming the field for
// non-finite or out-of-order times and for a bad anchor state.
TimeOfImpact board_time_of_impact(const BoardDistance& board, const MotionSetup& setup,
                                  const RigidBodyState& anchor, double anchor_time_s,
                                  double start_time_s, double horizon_s,
                                  const TimeOfImpactOptions& options = {});

// Velocity of the lens's material point at `point_world` (m/s): v + omega x (p - x_G).
Eigen::Vector3d point_velocity_world(const MotionModel& model, const RigidBodyState& state,
                                     const Eigen::Vector3d& point_world);

}  // namespace virtual_go
