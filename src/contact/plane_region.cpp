#include "virtual_go/contact/plane_region.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_go/common/validation.h"

namespace virtual_go {

PlaneRegion PlaneRegion::inside(const Eigen::Vector2d& center, const Eigen::Vector2d& half_extent) {
  PlaneRegion r;
  r.kind = Kind::inside_rectangle;
  r.center_world_m = center;
  r.half_extent_m = half_extent;
  return r;
}

PlaneRegion PlaneRegion::outside(const Eigen::Vector2d& center,
                                 const Eigen::Vector2d& half_extent) {
  PlaneRegion r = inside(center, half_extent);
  r.kind = Kind::outside_rectangle;
  return r;
}

double PlaneRegion::margin_m(const Eigen::Vector2d& point_world) const {
  if (kind == Kind::whole_plane) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d offset = (point_world - center_world_m).cwiseAbs();
  const double inside_margin =
      std::min(half_extent_m.x() - offset.x(), half_extent_m.y() - offset.y());
  return kind == Kind::inside_rectangle ? inside_margin : -inside_margin;
}

void validate_region(const std::string& field, const PlaneRegion& region) {
  if (region.kind == PlaneRegion::Kind::whole_plane) return;
  require_finite(field + ".center.x", region.center_world_m.x());
  require_finite(field + ".center.y", region.center_world_m.y());
  require_positive(field + ".half_extent.x", region.half_extent_m.x());
  require_positive(field + ".half_extent.y", region.half_extent_m.y());
}

}  // namespace virtual_go
