#include "virtual_go/world/nonsmooth_contact.h"

#include <vector>

namespace virtual_go {
namespace {

std::vector<IslandBody> one_body(const BoardDistance& board, const MotionSetup& setup,
                                 const RigidBodyState& state, bool board_enabled) {
  return {IslandBody{board, setup, state, board_enabled}};
}

}  // namespace

NonsmoothContact::NonsmoothContact(const BoardDistance& board, const MotionSetup& setup,
                                   const ContactMaterial& board_material,
                                   const ContactMaterial& table_material,
                                   const RigidBodyState& state, double t0_s,
                                   const NonsmoothContactOptions& options, bool board_enabled)
    // One member has no stone contact: the stone material is never used (the board's stands in).
    : island_(one_body(board, setup, state, board_enabled), board_material, table_material,
              board_material, t0_s, options) {}

NonsmoothOutcome NonsmoothContact::advance(double t_end_s, long max_steps) {
  const IslandOutcome island = island_.advance(t_end_s, max_steps);
  NonsmoothOutcome o;
  o.time_s = island.time_s;
  o.state = island.states.front();
  if (!island.left.empty()) {
    const IslandMemberEnd& e = island.left.front();
    o.end = e.end;
    o.plane = e.plane;
    o.contact = e.contact;
  }
  return o;
}

}  // namespace virtual_go
