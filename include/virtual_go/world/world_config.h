// Everything a World is made of (docs/physics.md, "World"): the stone (its motion setup and lens),
// the board and the table it stands on, the contact laws of the two surfaces, and the numerical
// options of the contact models. Defaults: a real-sized board, the placeholder materials of
// contact/material.h (unmeasured), a Zeno height of 1 um.
#pragma once

#include "virtual_go/contact/material.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/go/board.h"
#include "virtual_go/world/nonsmooth_contact.h"

namespace virtual_go {

struct WorldOptions {
  // How far (s) one time-of-impact search looks ahead; a flight that outlives it is searched
  // again from there. Each flight is searched once in practice (a fall from 1 m takes 0.45 s).
  double contact_search_horizon_s = 1.0;
  TimeOfImpactOptions time_of_impact;
  PlaneContactOptions plane_contact;  // its clearance_m is set by the world (the board's sides)
  NonsmoothContactOptions nonsmooth;
  // After a lift-off the stone leaves its plane with gap 0, normal velocity 0 and normal force 0:
  // the gap grows only at third order, so no lower bound can prove it apart at once. The flight
  // is probed at doubling times from 1 ns up to this (s) until the gap is resolvable and
  // opening; the search starts there. If the gap closes instead, the lift-off was round-off and
  // the fallback takes the contact.
  double lift_off_probe_s = 1e-3;
};

// WorldConfig::stone_contact's default (the node's ~contact/stone/enabled reads it too).
inline constexpr bool kDefaultStoneContact = true;

struct WorldConfig {
  WorldConfig(const MotionSetup& motion, const LensShape& shape) : motion(motion), shape(shape) {}

  MotionSetup motion;  // the stones' motion model and the gravity (m/s^2)
  LensShape shape;     // the stones' lens
  // Without the board there is no board and no table: stones fly forever (the node's
  // ~board/enabled false).
  bool board_enabled = true;
  BoardGeometry board;
  ContactMaterial board_material;  // stone on the board (top face, edges, sides)
  ContactMaterial table_material;  // stone on the table
  // Stone on stone (pair impacts and the island's stone contacts). A placeholder, unmeasured:
  // contact/material.h's defaults (e = 0.5, mu = 0.3), like the board's; slate on shell is
  // not measured yet.
  ContactMaterial stone_material;
  // Stones touch each other (pair times of impact, pair impacts, islands: docs/physics.md,
  // "Stone-stone contact in the world"): a dropped stone lands on, knocks and rests against its
  // neighbours. Off, stones pass through each other and each moves alone (what the world did
  // before issue 15; test_world keeps a variant). It was off until the pair search stopped
  // taking many tiny passes for stones side by side in plane contact and a stone dropped into
  // its slot between exactly touching neighbours finished; its work is in the WorkBudget.
  // Still dear: a stone thrown into a full board makes one island of every touching stone
  // (0.1-0.2 s of CPU per simulated ms; docs/physics.md).
  bool stone_contact = kDefaultStoneContact;
  double zeno_height_m = 1e-6;  // rebounds lower than this end the bouncing (docs/physics.md,
                                // "Impact")
  WorldOptions options;
};

// Throws InvalidArgument whose field() names the offending entry: "board/size" (via
// validate_board), "contact/board/friction", "contact/table/restitution",
// "contact/stone/friction", "contact/zeno_height", "world/contact_search_horizon",
// "nonsmooth/step_s", "gravity", "inertia" (a rigid body whose inertia is not axisymmetric has no
// closed-form flight).
void validate_world_config(const WorldConfig& config);

}  // namespace virtual_go
