// The two horizontal planes a stone can lie on, each with the region where it exists: the board's
// top face (inside the top rectangle) and the table (outside the board's footprint, and only
// while the stone is clear of the board's sides). A sustained contact on one of them has an
// exact model (PlaneContact); every other sustained contact goes to the fallback
// (docs/physics.md, "World").
#pragma once

#include <functional>
#include <optional>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/plane_region.h"
#include "virtual_go/go/board_distance.h"

namespace virtual_go {

struct SupportPlane {
  BoardFeature feature;   // top_face or table
  double height_m = 0.0;  // the plane is z = height_m
  PlaneRegion region;     // where the contact point may be
};

// The plane a stone touching the board at `contact` lies on, if it is one: the top face with the
// contact point inside the top rectangle by more than inside_margin_m, or the table with the
// contact point outside the board's footprint by more than it and the lens more than it away
// from the box. Otherwise (an edge, a corner, a side face, or too near the boundary) none.
std::optional<SupportPlane> support_plane(const BoardDistance& board, const BoardContact& contact,
                                          const LensPose& pose, double inside_margin_m);

// The clearance a plane contact on `plane` must keep to the rest of the board: none on the top
// face (a lens whose lowest point is on the face is above the whole box), the lens-box gap on
// the table (the board's sides).
std::function<double(const LensPose&)> support_plane_clearance(const BoardDistance& board,
                                                               const SupportPlane& plane);

// `state` moved vertically so that the lens touches the plane z = height_m exactly:
// z_G = height_m + reach(b_z) (docs/physics.md, "Contact geometry").
RigidBodyState placed_on_plane(const LensGeometry& lens, const RigidBodyState& state,
                               double height_m);

}  // namespace virtual_go
