// Inside PlaneContact (plane_contact.h): what stays fixed during a phase and the pieces every
// room of it uses. Each room is one source file:
//   plane_contact.cpp               set-up and checks, advance() and the handling of events
//   plane_contact_motion.cpp        the integrated coordinates, the right-hand side and the
//                                   sliding directions slaved to the motion near zero
//   plane_contact_dynamics.cpp      the contact forces of a mode (public: plane_contact_dynamics.h)
//   plane_contact_energy_guard.cpp  the energy guard and the plastic projection
//   plane_contact_events.cpp        the event functions
//   plane_contact_modes.cpp         the choice of the mode at an event
//   plane_contact_stepping.cpp      integrator steps, the kept trajectory and sampling
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "virtual_go/contact/dop853.h"
#include "virtual_go/contact/plane_contact.h"

namespace virtual_go::plane_contact_detail {

// Integrated coordinates: x_G, y_G; a quaternion (w, x, y, z) and the spin angle psi about the
// symmetry axis, the orientation being q = q~ (x) (cos psi/2, 0, 0, sin psi/2); v_x, v_y; omega
// (world). z_G, v_z, and whatever the mode holds stuck are derived (plane_contact_kinematics).
// For an axisymmetric stone (I1 = I2) the contact geometry, the inertia and so every force depend
// only on the axis b = R(q~) e_z: q~ turns with the part of omega across b and psi' = omega . b
// is a quadrature, so the fast spin of a tossed stone is no longer a fast rotation of the
// integrated quaternion (psi is folded into q~ at every step's start). Without that symmetry q~
// turns with all of omega and psi stays 0.
constexpr int kStateSize = 12;
using State = dop853::Vector<kStateSize>;
enum Index {
  kX = 0,
  kY = 1,
  kQw = 2,
  kQx = 3,
  kQy = 4,
  kQz = 5,
  kPsi = 6,
  kVx = 7,
  kVy = 8,
  kWx = 9,
};

enum class Trigger {
  part_switch,
  lift_off,
  region,
  tangential_zero,
  tangential_bound,
  rolling_zero,
  rolling_bound,
  spinning_zero,
  spinning_bound,
  clearance,
  tangential_layer,  // the slip speed crosses the edge of its direction layer (not reported)
  rolling_layer,     // the rolling speed does
};
constexpr int kTriggerCount = 12;

struct EventValues {
  std::array<double, kTriggerCount> g{};
  std::array<bool, kTriggerCount> active{};
};

// The result of choosing a mode at an event (or at the start).
struct ModeChoice {
  enum class Result { mode, lift_off, rest } result = Result::mode;
  PlaneContactMode mode;
  PlaneContactKinematics kinematics;  // projected onto the mode's constraints
};

// The laws of one phase: const after construction (the counters count the work of const
// look-ups too).
class PlaneContactLaws {
 public:
  PlaneContactLaws(const PlaneContactSetup& setup, const PlaneRegion& region,
                   const PlaneContactOptions& options);

  const PlaneContactSetup& setup() const { return setup_; }
  const PlaneRegion& region() const { return region_; }
  const PlaneContactOptions& options() const { return options_; }
  PlaneContactCounters& counters() const { return counters_; }

  // --- Coordinates and right-hand side (plane_contact_motion.cpp)
  State encode(const PlaneContactKinematics& k) const;
  // The kinematics of the state in `mode`. `full_orientation` false: the orientation is q~ alone
  // (enough for every force and event of an axisymmetric stone; no trigonometry).
  PlaneContactKinematics decode(const PlaneContactMode& mode, const State& y,
                                bool full_orientation = true) const;
  // dy/dt; `forces` and `kinematics` (optional) receive the forces solved on the way and the
  // kinematics they were solved at (decode(mode, y, false)).
  void rhs(const PlaneContactMode& mode, const State& y, State& dydt,
           PlaneContactForces* forces = nullptr,
           PlaneContactKinematics* kinematics = nullptr) const;
  // The quaternion rows of dy/dt alone (no force solve): after psi is folded into q~.
  void orientation_rates(const State& y, State& dydt) const;
  // q~ (x) rotation(psi) into q~, psi = 0; the rates follow (they are linear in q~).
  void fold_spin(State& y, State* dydt) const;
  // The per-component error scale of the integrator between y0 and y1.
  State error_scale(const State& y0, const State& y1) const;

  // --- Forces of a mode (plane_contact_motion.cpp; plane_contact_dynamics.cpp does the solve)
  // Throws IntegrationError when no consistent contact force exists.
  PlaneContactForces solve(const PlaneContactMode& mode, const PlaneContactKinematics& k) const;
  // The mode with the reference of each part marked `slaved` replaced by the direction its motion
  // is slaved to at k (see slaved_direction).
  PlaneContactMode slaved(const PlaneContactMode& mode, const PlaneContactKinematics& k) const;
  // Newton's method for the zero of the direction residual near the part's reference. `decide`:
  // also require what makes a part slaved at a step's start (a stable zero); within a step only
  // convergence is required, so the law stays smooth.
  bool slaved_direction(const PlaneContactMode& mode, const PlaneContactKinematics& k,
                        bool tangential, bool decide, Eigen::Vector3d& direction) const;

  // --- Energy guard (plane_contact_energy_guard.cpp)
  double energy(const PlaneContactKinematics& k) const;
  // k with (v_t, omega) scaled down so that its energy is at most `cap` (unchanged when it is).
  PlaneContactKinematics capped(const PlaneContactKinematics& k, const PlaneContactMode& mode,
                                double cap) const;
  // k with the velocities the mode holds at zero removed by a plastic impulse.
  PlaneContactKinematics projected(const PlaneContactKinematics& k,
                                   const PlaneContactMode& mode) const;

  // --- Event functions (plane_contact_events.cpp)
  // Which events the mode can meet and their values at k; `forces` at k if already solved.
  // `skip_clearance`: the clearance is left at 0 (the caller knows a positive bound of it).
  EventValues event_values(const PlaneContactKinematics& k, const PlaneContactMode& mode,
                           const PlaneContactForces* forces = nullptr,
                           bool skip_clearance = false) const;
  // The event function of `trigger` (positive while the mode holds).
  double event_value(Trigger trigger, const PlaneContactKinematics& k, const PlaneContactMode& mode,
                     const PlaneContactForces* forces = nullptr) const;

  // --- Mode choice (plane_contact_modes.cpp)
  // The mode at k on `part`, after an event: `snap` a part whose motion reached zero, `release`
  // a stuck part whose force reached its bound; `current` is the mode before the event.
  ModeChoice choose_mode(const PlaneContactKinematics& k, LensPart part,
                         std::optional<Trigger> snap, std::optional<Trigger> release,
                         const PlaneContactMode& current) const;

 private:
  bool is_static(const PlaneContactKinematics& k, PlaneContactMode* stuck_mode) const;
  Eigen::Vector3d release_direction(const PlaneContactMode& mode, const PlaneContactKinematics& k,
                                    bool tangential, const Eigen::Vector3d& hint) const;

  PlaneContactSetup setup_;
  PlaneRegion region_;
  PlaneContactOptions options_;
  bool axisymmetric_;  // I1 = I2 (or constant omega): psi is a quadrature
  mutable PlaneContactCounters counters_;
};

}  // namespace virtual_go::plane_contact_detail
