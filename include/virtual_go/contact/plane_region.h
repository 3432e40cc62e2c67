// The part of a horizontal plane that exists for a sustained contact: the whole plane, the inside
// of a rectangle (the board's top face) or its outside (the table around the board's footprint).
// A contact ends with `left_region` when its contact point crosses the boundary (docs/physics.md,
// "Sustained contact").
#pragma once

#include <Eigen/Core>
#include <string>

namespace virtual_go {

struct PlaneRegion {
  enum class Kind { whole_plane, inside_rectangle, outside_rectangle };

  Kind kind = Kind::whole_plane;
  Eigen::Vector2d center_world_m = Eigen::Vector2d::Zero();  // rectangle centre (x, y), m
  Eigen::Vector2d half_extent_m = Eigen::Vector2d::Zero();   // rectangle half sizes, m, > 0

  static PlaneRegion whole_plane() { return {}; }
  static PlaneRegion inside(const Eigen::Vector2d& center, const Eigen::Vector2d& half_extent);
  static PlaneRegion outside(const Eigen::Vector2d& center, const Eigen::Vector2d& half_extent);

  // A continuous function of the point (x, y), m, positive inside the region, zero on its
  // boundary, negative outside: min(hx - |dx|, hy - |dy|) for the inside of the rectangle (the
  // distance to the boundary there) and its negative for the outside; +infinity for the whole
  // plane. Contact events are located on its sign change.
  double margin_m(const Eigen::Vector2d& point_world) const;
  bool contains(const Eigen::Vector2d& point_world) const { return margin_m(point_world) > 0.0; }
};

// Throws InvalidArgument naming `field` for non-finite values or non-positive half extents.
void validate_region(const std::string& field, const PlaneRegion& region);

}  // namespace virtual_go
