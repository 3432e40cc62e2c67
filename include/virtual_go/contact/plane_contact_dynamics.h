// Forces and accelerations of a stone in sustained contact with a horizontal plane z = h0, for a
// given contact mode: the Newton-Euler equations with the contact point held on the plane
// (docs/physics.md, "Sustained contact").
//
//   m a_G = m g + F,   d/dt(I_w omega) = r x F + tau,   F = N e_z + F_t,   tau = tau_r + tau_s e_z
//
// The contact law has three parts, each free (no force: its coefficient is zero), sliding (at
// its bound against the motion) or stuck (held at zero motion by whatever force the
// acceleration-level constraint needs, valid while that force is inside its bound):
//   tangential (Coulomb, mu):         slip velocity u_t of the material point at P;  |F_t| <= mu N
//   rolling resistance (length l_r):  horizontal angular velocity omega_t;           |tau_r| <= l_r
//   N spinning friction (length l_s):   vertical angular velocity omega_z;             |tau_s| <=
//   l_s N
// N always keeps the contact (the second derivative of the gap is zero); N < 0 means lift-off.
// The unknown multipliers (N and the stuck forces and couples) follow from the acceleration
// constraints in closed form for each mode: what the stuck parts fix is eliminated, leaving a
// scalar, a 2 x 2 or (slip stuck, both rotations moving) a 3 x 3 system.
#pragma once

#include <Eigen/Geometry>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/contact/material.h"
#include "virtual_go/geometry/lens_geometry.h"

namespace virtual_go {

enum class ContactLaw { free, sliding, stuck };

// One part of the contact law in a mode.
struct ContactLawPart {
  ContactLaw law = ContactLaw::free;
  // Sliding only: the unit direction of the motion when the mode's current integrator step began
  // (horizontal for tangential and rolling, +/- e_z for spinning). The law opposes
  // sign(v . reference) v / |v|, which is v / |v| until v reaches zero and continues smoothly
  // through it, so the integrator's dense output stays accurate across the zero crossing where
  // the event (the motion stops) is located. In a layer around zero motion (speeds below
  // kSlipDirectionLayer, kRollDirectionLayer) it opposes the reference itself: there v's
  // direction is a fast variable (the law turns the motion at a rate ~ mu N / (m |v|): stiff
  // equations) or dominated by round-off (a part just released from stuck). There PlaneContact
  // keeps the reference on the direction the motion is slaved to, the stable consistent one (the
  // part's acceleration along it, see `slaved`), so a growing motion leaves the layer aligned
  // with its law and a shrinking one stops along it; without such a direction the reference is
  // the direction a moment before, and friction along it still dissipates until
  // v . reference reaches 0, which is the stop event.
  Eigen::Vector3d reference_world = Eigen::Vector3d::Zero();
  // Sliding inside the direction layer with a stable consistent direction near the reference:
  // within the current integrator step the law opposes that direction at each state (found from
  // the reference), not the fixed reference. Set by PlaneContact at each step's start; ignored
  // by solve_plane_contact.
  bool slaved = false;
  // Which side of the direction layer the law is on. PlaneContact fixes it for whole integrator
  // steps (inside: the reference or the slaved direction; outside: the motion's direction), so the
  // law is smooth within every step, and ends a step where the speed crosses the layer's edge
  // (an event located on the dense output, not a cascade of ever smaller steps at the jump).
  // by_speed (the default): decided by the speed at each state.
  enum class Layer { by_speed, inside, outside } layer = Layer::by_speed;
};

struct PlaneContactMode {
  LensPart part = LensPart::bottom_cap;  // the part of the lens touching the plane
  ContactLawPart tangential, rolling, spinning;
};

// What stays constant during a contact phase.
struct PlaneContactSetup {
  MotionModel model;
  LensGeometry lens;
  Eigen::Vector3d gravity_world;  // m/s^2
  double plane_height_m;          // h0: the plane is z = h0, its normal +z
  ContactMaterial material;
};

// The stone on the plane with everything the mode constrains derived from the free coordinates.
struct PlaneContactKinematics {
  Eigen::Vector3d position_world;  // x_G, m; z = h0 - r_z (the contact point on the plane)
  Eigen::Quaterniond orientation;  // body -> world, unit
  Eigen::Vector3d velocity_world;  // v_G, m/s; v_z keeps the gap rate 0 (and v_t when stuck)
  Eigen::Vector3d angular_velocity_world;  // rad/s; stuck components exactly 0
  Eigen::Vector3d axis_world;              // b = R(q) e_z
  Eigen::Vector3d offset_world;            // r = P - x_G, m
  Eigen::Vector3d offset_rate_world;       // dr/dt, m/s
  Eigen::Matrix3d inertia_world;           // kg m^2
  Eigen::Matrix3d inverse_inertia_world;

  // Horizontal velocity of the material point at P, m/s (z component 0).
  Eigen::Vector3d slip_velocity() const;
  // Horizontal part of the angular velocity, rad/s (z component 0).
  Eigen::Vector3d rolling_velocity() const {
    return {angular_velocity_world.x(), angular_velocity_world.y(), 0.0};
  }
  double spin_velocity() const { return angular_velocity_world.z(); }  // rad/s
};

// Builds the kinematics of the stone touching the plane with `mode.part`: the orientation is
// normalised, z_G and v_z are derived, stuck angular components are set to exactly zero and, when
// the tangential part is stuck, v_t = -(omega x r)_t (the material point at P does not move).
PlaneContactKinematics plane_contact_kinematics(const PlaneContactSetup& setup,
                                                const PlaneContactMode& mode,
                                                const Eigen::Vector2d& position_xy_world,
                                                const Eigen::Quaterniond& orientation,
                                                const Eigen::Vector2d& velocity_xy_world,
                                                const Eigen::Vector3d& angular_velocity_world);

struct PlaneContactForces {
  bool solved = false;  // false when the constraint system is singular
  double normal_force_n = 0.0;
  Eigen::Vector3d friction_force_world = Eigen::Vector3d::Zero();        // F_t at P, horizontal, N
  Eigen::Vector3d rolling_couple_world = Eigen::Vector3d::Zero();        // tau_r, horizontal, N m
  double spinning_couple_nm = 0.0;                                       // tau_s about +z, N m
  Eigen::Vector3d linear_acceleration_world = Eigen::Vector3d::Zero();   // a_G, m/s^2
  Eigen::Vector3d angular_acceleration_world = Eigen::Vector3d::Zero();  // rad/s^2
  // d/dt of the slip velocity (horizontal), m/s^2: a_G + alpha x r + omega x dr/dt.
  Eigen::Vector3d slip_acceleration_world = Eigen::Vector3d::Zero();
};

// The contact forces and the accelerations they cause, for the mode (sliding directions as
// described at ContactLawPart).
PlaneContactForces solve_plane_contact(const PlaneContactSetup& setup, const PlaneContactMode& mode,
                                       const PlaneContactKinematics& kinematics);

// Motion below these is zero: a part is stuck when its motion is this small where a mode is
// chosen (and it is then snapped to exactly zero), and a sliding part this slow opposes its
// reference direction. A contact point creeping at 1e-12 m/s moves a picometre a second.
constexpr double kZeroSlipSpeed = 1e-12;     // m/s
constexpr double kZeroAngularSpeed = 1e-10;  // rad/s (1e-12 m/s at the rim)
// The layer around zero motion where sliding parts follow their reference direction. 1e-4 m/s:
// above it the direction's relaxation rate mu g / |v| (~3e4 /s) no longer limits the
// integrator's steps much; below it the slaved direction is within ~1e-2 rad of the motion's
// (measured after a release).
constexpr double kSlipDirectionLayer = 1e-4;  // m/s
constexpr double kRollDirectionLayer = 1e-4;  // rad/s (1e-6 m/s at the rim)

// The sliding direction of a part (unit) from its velocity and reference, as the law uses it with
// the layer decided by speed (a layer_speed of 0: the motion's direction unless it is zero).
Eigen::Vector3d sliding_direction(const Eigen::Vector3d& velocity, const Eigen::Vector3d& reference,
                                  double layer_speed);

// Total energy (J): kinetic 1/2 m v^2 + 1/2 omega . I_w omega, plus potential -m g . x_G.
double plane_contact_energy(const PlaneContactSetup& setup, const PlaneContactKinematics& k);

}  // namespace virtual_go
