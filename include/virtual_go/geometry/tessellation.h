// Closed triangle mesh of the lens surface, body frame, for display (rviz) and volume checks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "virtual_go/geometry/lens_shape.h"

namespace virtual_go {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside

  double enclosed_volume() const;  // divergence theorem; exact for the polyhedron
};

// `segments` around the rim (>= 3), `rings` from the rim to each pole (>= 1); InvalidArgument
// with field "segments" or "rings" otherwise.
TriangleMesh tessellate_lens(const LensShape& shape, int segments, int rings);

}  // namespace virtual_go
