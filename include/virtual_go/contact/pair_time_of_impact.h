// The exact time of first contact between two stones, each in closed-form flight or resting
// (docs/physics.md, "Stone–stone contact (primitives)"). Gravity acts on both flying stones
// alike, so it cancels in their relative motion: the centres' separation moves in a straight
// line (a parabola only against a resting stone, whose weight the board carries). The
// orientations are the torque-free closed form, in which each symmetry axis precesses uniformly
// (|b'| constant) and a spin about the axis moves no surface point.
//
// The search is conservative advancement on the gap along the present closest normal n (a lower
// bound of the distance at every time, lens_pair_distance.h):
//   g_n(t) = n . (x_B - x_A)(t) - reach_A(b_A(t) . n) - reach_B(b_B(t) . n),
//   |d reach_k / dt| <= d_k |b_k'|,  |d^2 reach_k / dt^2| <= kappa_k |b_k'|^2 + d_k |Omega_k|
//   |b_k'|
// (kappa_k the rim's largest curvature of the reach, Omega_k the precession). Three lower
// parabolas follow (the reach at its largest, the rate bound, the exact slope with the curvature
// bound); the step is the largest of their first roots, so no step passes a contact. Near the
// contact the exact-slope parabola makes each step a safeguarded Newton step from the contact-
// free side (the polish): the result is never after the first contact, and the gap there is zero
// to round-off. A query: the flights are not changed.
#pragma once

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/geometry/lens_pair_distance.h"

namespace virtual_go {

// One stone's motion: the closed form through `anchor` at `anchor_time_s`. A supported stone
// (resting on the board) feels no gravity: with zero velocities it stays where it is.
struct StoneMotion {
  const LensGeometry& lens;
  const MotionSetup& setup;
  const RigidBodyState& anchor;
  double anchor_time_s = 0.0;
  bool supported = false;
};

struct PairTimeOfImpactOptions {
  double polish_gap_m = 1e-9;       // below this gap steps count as polishing
  double touch_tolerance_m = 1e-9;  // closer and separating: let them leave (just collided)
  int max_steps = 100000;           // then `exhausted`: contact-free up to time_s
};

struct PairTimeOfImpact {
  bool hit = false;
  bool exhausted = false;
  double time_s = 0.0;  // the contact time, else the horizon (or how far the search got), s
  RigidBodyState state_a, state_b;  // at time_s
  LensPairContact contact;          // at time_s: gap (~0 at a hit), normal A -> B, witnesses
  // -(n . (u_B - u_A)) at the witness points, m/s: > 0 approaching. A hit with a speed <= 0 at
  // the start time means the stones already overlap by more than the touch tolerance.
  double approach_speed_mps = 0.0;
  int advancement_steps = 0;
  int polish_steps = 0;
};

// First contact between the two stones, searched from start_time_s up to horizon_s (finite,
// in order). Throws InvalidArgument naming the field for non-finite or out-of-order times, bad
// options or a bad anchor state, and (field "inertia") for a rigid_body model that is not
// axisymmetric.
PairTimeOfImpact pair_time_of_impact(const StoneMotion& a, const StoneMotion& b,
                                     double start_time_s, double horizon_s,
                                     const PairTimeOfImpactOptions& options = {});

}  // namespace virtual_go
