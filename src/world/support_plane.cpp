#include "virtual_go/world/support_plane.h"

namespace virtual_go {

std::optional<SupportPlane> support_plane(const BoardDistance& board, const BoardContact& contact,
                                          const LensPose& pose, double inside_margin_m) {
  const BoardGeometry& geometry = board.board();
  const Eigen::Vector2d point = contact.lens.point_world.head<2>();
  if (contact.feature.kind == BoardFeatureKind::top_face) {
    SupportPlane plane{contact.feature, geometry.top_z_m(),
                       PlaneRegion::inside(Eigen::Vector2d::Zero(), geometry.half_extent_m())};
    if (plane.region.margin_m(point) > inside_margin_m) return plane;
    return std::nullopt;
  }
  if (contact.feature.kind == BoardFeatureKind::table) {
    SupportPlane plane{contact.feature, geometry.table_z_m(),
                       PlaneRegion::outside(Eigen::Vector2d::Zero(), geometry.half_extent_m())};
    if (plane.region.margin_m(point) > inside_margin_m &&
        board.box(pose).lens.gap_m > inside_margin_m) {
      return plane;
    }
  }
  return std::nullopt;
}

std::function<double(const LensPose&)> support_plane_clearance(const BoardDistance& board,
                                                               const SupportPlane& plane) {
  if (plane.feature.kind != BoardFeatureKind::table) return nullptr;
  // The BoardDistance is copied into the function: it outlives the caller's.
  return [board](const LensPose& pose) { return board.box(pose).lens.gap_m; };
}

RigidBodyState placed_on_plane(const LensGeometry& lens, const RigidBodyState& state,
                               double height_m) {
  RigidBodyState out = state;
  const double axis_z = (state.orientation * Eigen::Vector3d::UnitZ()).z();
  out.position_world.z() = height_m + lens.reach(axis_z);
  return out;
}

}  // namespace virtual_go
