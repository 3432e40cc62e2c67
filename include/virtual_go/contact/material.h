// The contact law's parameters for one pair of surfaces (stone on board, stone on table).
// No published measurements of Go stones exist: the defaults are unmeasured placeholders, to
// be fitted (drop sound for the restitution, tilt-to-slip angle for the friction, video of the
// rocking and spin decay for the two lengths). See docs/physics.md, "Contact materials".
#pragma once

#include <string>

namespace virtual_go {

struct ContactMaterial {
  // Stronge's energetic coefficient e* in [0, 1]: the restitution work is -e*^2 times the
  // compression work, so no impact can add energy (with friction or without).
  double restitution = 0.5;
  double friction = 0.3;               // Coulomb coefficient mu >= 0 (static = kinetic)
  double rolling_resistance_m = 5e-6;  // l_r >= 0, m: the rolling couple is at most l_r N
  double spinning_friction_m = 15e-6;  // l_s >= 0, m: the spinning couple is at most l_s N
};

// Throws InvalidArgument whose field() is `field` + "/restitution" (etc., e.g.
// "contact/board/friction"), naming the value and the limit.
void validate_material(const std::string& field, const ContactMaterial& material);

}  // namespace virtual_go
