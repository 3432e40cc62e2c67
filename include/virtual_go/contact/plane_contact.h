// Sustained contact of one stone with a horizontal plane z = h0 (the board's top face or the
// table): sliding, rolling and rocking, spinning, on a cap or on the rim, with Coulomb sliding
// friction and set-valued rolling resistance and spinning friction (plane_contact_dynamics.h;
// docs/physics.md, "Sustained contact").
//
// The phase starts from a state already on the plane (gap 0, normal velocity 0 after an impact,
// or a stone placed there) and integrates the Newton-Euler equations in coordinates where the
// stone can neither sink nor float: z_G and v_z (and v_t while the contact point sticks, and
// the stuck angular components) are derived, never integrated, so every state handed out has
// gap 0 to round-off. Between mode changes the motion is smooth and is integrated by Dormand and
// Prince's adaptive 8(5,3) method with dense output (dop853.h); for an axisymmetric stone the spin
// about its axis is a quadrature, not part of the integrated rotation. Every mode change is an
// event located on the dense output by a bracketing root finder (TOMS 748):
//   slip_stop / roll_stop / spin_stop  the sliding, rolling or spinning motion reaches zero; it is
//                                      snapped to exactly zero by a plastic impulse (energy can
//                                      only fall) and stays stuck while the law can hold it
//   slip_start / roll_start / spin_start  the force or couple a stuck part needs reaches its bound
//   cap_to_rim / rim_to_cap            |b_z| crosses d/R (continuous: no impulse)
//   lift_off                           N reaches 0: the stone flies (the phase ends)
//   left_region                        the contact point leaves the plane's region (ends)
//   obstacle                           the optional clearance to other obstacles reaches 0:
//                                      the stone touches something besides the plane (ends)
//   rest                               everything stuck, velocities exactly 0 and the static
//                                      inequalities hold: the state is frozen (ends)
// When several parts have zero motion at once the mode is chosen by trying all of them stuck
// and releasing the one whose needed force or couple exceeds its bound most, in the direction
// consistent with the dynamics (the sliding acceleration parallel to the released direction),
// until the rest hold. Energy never increases: the laws only dissipate or conserve, and a guard
// scales (v_G, omega) down if the integrator's error raised the energy at a step end (the
// constraints are linear and homogeneous in the velocities, so scaling keeps them).
#pragma once

#include <functional>
#include <limits>
#include <memory>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/plane_contact_dynamics.h"
#include "virtual_go/contact/plane_region.h"
#include "virtual_go/geometry/lens_distance.h"

namespace virtual_go {

enum class PlaneContactEvent {
  none,  // the requested time was reached
  slip_stop,
  slip_start,
  roll_stop,
  roll_start,
  spin_stop,
  spin_start,
  cap_to_rim,
  rim_to_cap,
  lift_off,
  left_region,
  obstacle,
  rest,
};

// "none", "slip_stop", ... (the enumerator's name).
const char* plane_contact_event_name(PlaneContactEvent event);

struct PlaneContactOutcome {
  double time_s = 0.0;
  PlaneContactEvent event = PlaneContactEvent::none;
  RigidBodyState state;   // at time_s, after the event (on the plane: gap 0)
  PlaneContactMode mode;  // the mode from time_s on
  bool finished = false;  // the phase is over: lift_off, left_region, obstacle or rest
};

struct PlaneContactOptions {
  double relative_tolerance = 1e-12;  // of the integrator, per step (maximum norm)
  double absolute_tolerance = 1e-14;  // of the integrator (m, m/s, rad/s, quaternion units)
  double max_step_s = 0.1;            // longest integrator step, s
  // Events are looked for at least this often (s): at step ends, and within a longer step on its
  // dense output. A sign change between two looks is found; two within one are not.
  double event_resolution_s = 5e-3;
  double initial_step_s = 1e-4;                 // first trial step after a mode change, s
  double gap_tolerance_m = 1e-9;                // accepted |gap| of the initial state, m
  double normal_velocity_tolerance_mps = 1e-6;  // accepted |u_n| of the initial state, m/s
  // Optional: the signed distance (m) from the stone at a pose to the obstacles other than the
  // plane (the board's sides for a stone on the table), positive while none touches it. The
  // phase ends with `obstacle` where it reaches 0 (located like every event, on the dense
  // output). It must be continuous in the pose and change by no more than the farthest any point
  // of the lens moves (as a distance to fixed obstacles does): while a step cannot have used up
  // the last value found, it is not evaluated again. Empty: there is nothing else to touch.
  std::function<double(const LensPose&)> clearance_m;
};

// Work done, for benchmarks (a resting or finished phase adds nothing).
struct PlaneContactCounters {
  long steps = 0;            // accepted integrator steps
  long rhs_evaluations = 0;  // right-hand sides (each one force solve) inside the integrator
  long extra_solves = 0;     // force solves for events, root finding and mode choice
  long events = 0;           // mode changes, including those not reported (a rocking turn)
  long energy_guard_scalings = 0;
};

class PlaneContact {
 public:
  // `state` must touch the plane z = plane_height_m (|gap| <= options.gap_tolerance_m) with a
  // normal velocity of the contact point within options.normal_velocity_tolerance_mps, and its
  // contact point inside `region`; the residual normal velocity is removed by a plastic impulse
  // (energy can only fall), and the clearance (if given) must be positive. Throws
  // InvalidArgument naming what is wrong.
  PlaneContact(const MotionModel& model, const LensGeometry& lens,
               const Eigen::Vector3d& gravity_world, double plane_height_m,
               const PlaneRegion& region, const ContactMaterial& material,
               const RigidBodyState& state, double t0_s,
               const PlaneContactOptions& options = PlaneContactOptions());
  ~PlaneContact();
  PlaneContact(const PlaneContact& other);  // a full copy: the copy goes on independently
  PlaneContact& operator=(const PlaneContact& other);
  PlaneContact(PlaneContact&&) noexcept;
  PlaneContact& operator=(PlaneContact&&) noexcept;

  // Integrates up to t_end_s (>= time_reached()) or to the first event the world must see
  // (every mode change, and the end of the phase), whichever comes first. Mode changes that
  // leave the mode as it was (a rocking stone turning against its rolling resistance) are
  // handled inside. After `rest` the state is frozen and further calls cost nothing; after
  // `lift_off`, `left_region` or `obstacle` the phase is over and only that time may be asked
  // for again.
  // Throws InvalidArgument for a non-finite t_end_s or one before time_reached(), and
  // IntegrationError (state unchanged up to the last completed step) when no consistent contact
  // force exists (Painleve's paradox: for a size-33 lens only at mu >= 0.986, found over 2e5
  // random orientations; a sliding phase may then also end in a spurious lift_off), the mode
  // cannot be resolved, or the integrator fails.
  // `max_steps` is a work budget: when this call has taken that many integrator steps without
  // reaching t_end_s or an event, it returns `none` at the last step's end (time_reached() <
  // t_end_s, the state there exact as ever) and the next call goes on from there. Throws
  // InvalidArgument for a negative budget.
  PlaneContactOutcome advance(double t_end_s, long max_steps = std::numeric_limits<long>::max());

  // The state at t_s in [window start, time_reached()], where the window starts where the
  // previous call of advance() returned (so the caller can sample a time grid behind it), or at
  // most 4096 integrator steps back when one call went further. Throws InvalidArgument outside.
  RigidBodyState state_at(double t_s) const;
  // The contact forces at t_s (same range as state_at).
  PlaneContactForces forces_at(double t_s) const;

  double time_reached() const;
  bool finished() const;
  const PlaneContactMode& mode() const;
  const PlaneContactSetup& setup() const;
  const PlaneContactCounters& counters() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace virtual_go
