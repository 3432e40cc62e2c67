// The fallback for sustained contacts that have no exact model here: a cap or the rim pivoting on
// one of the board's edges or corners, a stone against a side face, on the table and against a
// side at once (docs/physics.md, "World"). A fixed-step nonsmooth scheme of the Moreau-Jean type
// with e = 0 and Coulomb friction (Moreau 1988; Jean 1999; Acary & Brogliato, "Numerical Methods
// for Nonsmooth Dynamical Systems", 2008), built from the exact pieces:
//   1. exact free flight over the sub-step (closed form, ExactMotion);
//   2. positions out of any overlap: the centre translated along the contact normal by the
//      overlap (Gauss-Seidel over the box and the table, at most two contacts: a strictly convex
//      lens touches a convex box in one point);
//   3. velocities: every contact within the margin that is still approaching gets a plastic
//      impulse (resolve_impact with e* = 0: Coulomb friction integrated through the impulse, so
//      each one can only remove energy), Gauss-Seidel over the contacts until none approaches;
//   4. an energy guard: if the position correction raised the energy above the previous
//      sub-step's, (v, L) are scaled down (every velocity constraint is linear and homogeneous in
//      them, so u_n >= 0 is kept). The phase never raises the energy.
// What is NOT exact: the motion is first order in the sub-step (the contact force is an impulse
// per sub-step), a new impact inside the phase is plastic (no bounce), the rolling resistance
// and spinning friction are not applied, and rest is declared by a speed threshold held over a
// time. What is kept: no handed-out state overlaps (gap >= -1e-12 m), no energy is created,
// Coulomb's cone holds for every impulse.
//
// The sub-steps lie on a fixed lattice t0 + k h from the phase's start, so the motion does not
// depend on the times it is sampled at: a sample between two lattice points is a partial sub-step
// (the same four stages over the shorter time) that is not committed.
//
// The phase ends at a lattice point when (checked in this order)
//   plane      exactly one contact is left, it carries load, and it is the top face or the table
//              with the contact point inside its region by plane_margin_m: the exact plane model
//              takes over;
//   rest       every speed stayed below rest_speed_m_s for rest_time_s (then v = L = 0 exactly);
//   separated  no contact carried load in the sub-step and the exact time of impact finds the
//              free flight from there contact-free for separation_time_s.
#pragma once

#include <limits>
#include <optional>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/material.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/world/support_plane.h"

namespace virtual_go {

struct NonsmoothContactOptions {
  double step_s = 1e-4;  // the sub-step h, s
  // Contacts with a gap up to this (m) count as touching: an approach there is stopped.
  double contact_margin_m = 1e-9;
  // The exact flight must be contact-free this long (s) for the phase to end in flight.
  double separation_time_s = 1e-3;
  // The plane model takes over only with the contact point this far (m) inside its region:
  // a hysteresis against switching back and forth at the board's edge.
  double plane_margin_m = 1e-5;
  // Rest: the centre's speed and the rim's speed |omega| a below this (m/s) ...
  double rest_speed_m_s = 1e-5;
  // ... for this long (s).
  double rest_time_s = 0.01;
  int max_sweeps = 32;  // Gauss-Seidel sweeps over the contacts per sub-step
};

// Throws InvalidArgument naming the option ("nonsmooth/step_s", ...).
void validate_nonsmooth_options(const NonsmoothContactOptions& options);

enum class NonsmoothEnd { none, separated, plane, rest };

struct NonsmoothOutcome {
  double time_s = 0.0;
  NonsmoothEnd end = NonsmoothEnd::none;  // none: the requested time was reached
  RigidBodyState state;                   // at time_s
  std::optional<SupportPlane> plane;      // end == plane: the plane the stone lies on
  BoardContact contact;                   // end == plane: the contact on it
};

// Work and accuracy figures, for tests and benchmarks.
struct NonsmoothCounters {
  long steps = 0;        // committed sub-steps
  long samples = 0;      // partial sub-steps for samples between lattice points
  long impulses = 0;     // plastic impulses applied
  long projections = 0;  // position corrections
  long energy_guard_scalings = 0;
  long separation_searches = 0;          // exact time-of-impact searches for the separated test
  double deepest_overlap_m = 0.0;        // deepest overlap a free sub-step produced (corrected), m
  double largest_energy_excess_j = 0.0;  // energy above the cap the guard could not remove
                                         // (all velocities zero already), J
};

class NonsmoothContact {
 public:
  // `state` at t0_s (world time line, s) touches the board or the table (or nearly).
  // Throws InvalidArgument naming the option or field.
  NonsmoothContact(const BoardDistance& board, const MotionSetup& setup,
                   const ContactMaterial& board_material, const ContactMaterial& table_material,
                   const RigidBodyState& state, double t0_s,
                   const NonsmoothContactOptions& options = NonsmoothContactOptions());

  // Commits the sub-steps up to t_end_s (>= the time of the previous call) and returns the state
  // there, or the first end of the phase (then the phase is over: only that time may be asked
  // for again). Throws InvalidArgument for a non-finite or earlier time, or a negative budget.
  // `max_steps` is a work budget: when this call has committed that many sub-steps without
  // reaching t_end_s or an end, it returns `none` at the last lattice point reached (time_s <
  // t_end_s) and the next call goes on from there.
  NonsmoothOutcome advance(double t_end_s, long max_steps = std::numeric_limits<long>::max());

  double start_time() const { return t0_; }
  double lattice_time() const { return lattice(steps_); }  // time of the last committed state
  const RigidBodyState& lattice_state() const { return state_; }
  bool finished() const { return finished_.has_value(); }
  const NonsmoothCounters& counters() const { return counters_; }
  const NonsmoothContactOptions& options() const { return options_; }

 private:
  struct SubStep {
    RigidBodyState state;
    bool loaded = false;      // a contact needed a correction or an impulse
    int contacts = 0;         // contacts within the margin at the end
    BoardContact contact[2];  // those contacts
  };
  SubStep sub_step(const RigidBodyState& from, double h_s, double energy_cap_j, bool commit);
  // Scales velocity and angular momentum so that the energy becomes energy_j (0 when the
  // potential energy alone exceeds it); returns the factor.
  double scale_kinetic_energy(RigidBodyState& s, double energy_j) const;
  double lattice(long k) const { return t0_ + static_cast<double>(k) * options_.step_s; }
  double energy(const RigidBodyState& s) const;
  std::optional<NonsmoothOutcome> ending(const SubStep& step, double t);

  BoardDistance board_;
  MotionSetup setup_;
  ContactMaterial board_plastic_, table_plastic_;
  NonsmoothContactOptions options_;
  double t0_;
  long steps_ = 0;
  RigidBodyState state_;  // at lattice(steps_)
  double energy_ = 0.0;   // of state_
  long calm_steps_ = 0;
  double reached_;
  std::optional<NonsmoothOutcome> finished_;
  NonsmoothCounters counters_;
};

}  // namespace virtual_go
