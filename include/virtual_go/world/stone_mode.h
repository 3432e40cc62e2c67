// What a stone in the world is doing, one state per stone (docs/physics.md, "World"), which
// decides the work it costs per advance: a flight is sampled in closed form and compared with its
// cached contact time; a contact is integrated by its model; a resting stone is frozen and costs
// nothing. Every change of state goes through transition(), which holds the one table of the
// changes the world makes (a change not in it is a bug: std::logic_error).
#pragma once

#include <string>

namespace virtual_go {

enum class StoneMode {
  flight,             // free flight in closed form, between contacts
  plane_contact,      // sustained contact on one horizontal plane (the board's top face or the
                      // table): the exact model, PlaneContact
  nonsmooth_contact,  // any other contact (an edge, a corner, a side face, two contacts): the
                      // fixed-step fallback, NonsmoothContact
  resting,            // exact rest: velocities exactly zero, the pose frozen bit for bit
};

// The table of transitions (from -> to: causes):
//   flight            -> flight: an impact that rebounds (board or stone); a command (set_state)
//                     -> plane_contact: a Zeno impact or a touching start on the face or table
//                     -> nonsmooth_contact: a contact on an edge, corner or side; a sustained
//                        stone-stone contact (an island); a search that
//                        cannot move; a lift-off that was round-off; too many transitions at
//                        one instant
//   plane_contact     -> flight: lift-off; a command
//                     -> nonsmooth_contact: left its region, an obstacle, no consistent force
//                     -> resting: exact rest
//   nonsmooth_contact -> flight: separation; a command
//                     -> plane_contact: the contact became one plane
//                     -> nonsmooth_contact: restarted (a plane refused the state)
//                     -> resting: settled
//   resting           -> flight: a command wakes it
//                     -> nonsmooth_contact: a stone hits it, or an awake neighbour touches it
//                        (it joins that stone's island)
bool is_transition(StoneMode from, StoneMode to);
// `to` if from -> to is in the table; std::logic_error naming both otherwise.
StoneMode transition(StoneMode from, StoneMode to);

bool in_contact(StoneMode mode);  // plane_contact or nonsmooth_contact

// "flight", "plane_contact", "nonsmooth_contact", "resting".
std::string stone_mode_name(StoneMode mode);

// The contact model of a mode, for callers that ask which model runs (derived from the mode,
// never stored).
enum class ContactPhase {
  none,       // not in contact (flight or resting)
  plane,      // plane_contact
  nonsmooth,  // nonsmooth_contact
};
ContactPhase contact_phase(StoneMode mode);
std::string contact_phase_name(ContactPhase phase);  // "none", "plane", "nonsmooth"

}  // namespace virtual_go
