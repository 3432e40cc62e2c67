// Inside NonsmoothIsland (nonsmooth_island.h): the pieces more than one of its rooms uses. Rooms:
//   nonsmooth_island.cpp           options, construction, the lattice driver and the members' ends
//   nonsmooth_island_energy.cpp    the energy guard and a free island's conserved totals
//   nonsmooth_island_contacts.cpp  contact detection and the position corrections (step 2)
//   nonsmooth_island_sub_step.cpp  one sub-step and its velocity stage (step 3)
#pragma once

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/go/board_distance.h"

namespace virtual_go::nonsmooth_island_detail {

inline bool apart_by_bounds(const BoardDistance& a, const RigidBodyState& sa,
                            const BoardDistance& b, const RigidBodyState& sb, double margin_m) {
  // A lens lies within the sphere of its rim radius about its centre.
  const double reach = a.lens().half_width() + b.lens().half_width() + margin_m;
  return (sb.position_world - sa.position_world).squaredNorm() > reach * reach;
}

}  // namespace virtual_go::nonsmooth_island_detail
