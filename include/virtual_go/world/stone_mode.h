// What a stone in the world is doing, which decides the work it costs per advance (docs/physics.md,
// "World"): a flight is sampled in closed form and compared with its cached contact time; a
// contact is integrated; a resting stone is frozen and costs nothing.
#pragma once

#include <string>

namespace virtual_go {

enum class StoneMode {
  flight,   // free flight in closed form, between contacts
  contact,  // sustained contact (ContactPhase says which model)
  resting,  // exact rest: velocities exactly zero, the pose frozen bit for bit
};

// The model of a sustained contact.
enum class ContactPhase {
  none,       // not in contact (flight or resting)
  plane,      // on one horizontal plane (the board's top face or the table): PlaneContact
  nonsmooth,  // anything else (an edge, a corner, a side face, two contacts): the fixed-step
              // fallback, NonsmoothContact
};

std::string stone_mode_name(StoneMode mode);         // "flight", "contact", "resting"
std::string contact_phase_name(ContactPhase phase);  // "none", "plane", "nonsmooth"

}  // namespace virtual_go
