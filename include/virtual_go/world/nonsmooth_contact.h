// The fallback for sustained contacts of one stone that have no exact model here: a cap or the
// rim pivoting on one of the board's edges or corners, a stone against a side face, on the table
// and against a side at once (docs/physics.md, "World"). It is the island solver
// (nonsmooth_island.h: the scheme, its guarantees and its ends) with one member: a strictly
// convex lens touches the convex box in one point, so there are at most two contacts, the box's
// and the table's.
//
// The phase ends at a lattice point when (checked in this order)
//   plane      exactly one contact is left, it carries load, and it is the top face or the table
//              with the contact point inside its region by plane_margin_m: the exact plane model
//              takes over;
//   rest       every speed stayed below rest_speed_mps for rest_time_s (then v = L = 0 exactly);
//   separated  no contact carried load in the sub-step and the exact time of impact finds the
//              free flight from there contact-free for separation_time_s.
// With board_enabled false (a World whose board is switched off, whose island was dissolved by a
// command on another member) there is nothing to touch: the stone flies exactly for one sub-step
// and ends `separated`.
#pragma once

#include <limits>
#include <optional>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/material.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/world/nonsmooth_island.h"
#include "virtual_go/world/support_plane.h"

namespace virtual_go {

struct NonsmoothOutcome {
  double time_s = 0.0;
  NonsmoothEnd end = NonsmoothEnd::none;  // none: the requested time was reached
  RigidBodyState state;                   // at time_s
  std::optional<SupportPlane> plane;      // end == plane: the plane the stone lies on
  BoardContact contact;                   // end == plane: the contact on it
};

class NonsmoothContact {
 public:
  // `state` at t0_s (world time line, s) touches the board or the table (or nearly).
  // Throws InvalidArgument naming the option or field.
  NonsmoothContact(const BoardDistance& board, const MotionSetup& setup,
                   const ContactMaterial& board_material, const ContactMaterial& table_material,
                   const RigidBodyState& state, double t0_s,
                   const NonsmoothContactOptions& options = NonsmoothContactOptions(),
                   bool board_enabled = true);

  // Commits the sub-steps up to t_end_s (>= the time of the previous call) and returns the state
  // there, or the first end of the phase (then the phase is over: only that time may be asked
  // for again). Throws InvalidArgument for a non-finite or earlier time, or a negative budget.
  // `max_steps` is a work budget: when this call has committed that many sub-steps without
  // reaching t_end_s or an end, it returns `none` at the last lattice point reached (time_s <
  // t_end_s) and the next call goes on from there.
  NonsmoothOutcome advance(double t_end_s, long max_steps = std::numeric_limits<long>::max());

  double start_time() const { return island_.start_time(); }
  double lattice_time() const { return island_.lattice_time(); }  // of the last committed state
  const RigidBodyState& lattice_state() const { return island_.lattice_state(0); }
  bool finished() const { return island_.finished(); }
  const NonsmoothCounters& counters() const { return island_.counters(); }
  const NonsmoothContactOptions& options() const { return island_.options(); }

 private:
  NonsmoothIsland island_;
};

}  // namespace virtual_go
