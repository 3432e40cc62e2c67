#include "virtual_go/geometry/tessellation.h"

#include <cmath>

#include "virtual_go/common/validation.h"

namespace virtual_go {

double TriangleMesh::enclosed_volume() const {
  // Sum of signed tetrahedra (origin, a, b, c): exact for a closed, consistently oriented mesh.
  double six_volume = 0.0;
  for (const auto& t : triangles) {
    six_volume += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]]));
  }
  return six_volume / 6.0;
}

TriangleMesh tessellate_lens(const LensShape& shape, int segments, int rings) {
  if (segments < 3) {
    throw InvalidArgument("segments",
                          "tessellation segments must be >= 3, got " + std::to_string(segments));
  }
  if (rings < 1) {
    throw InvalidArgument("rings", "tessellation rings must be >= 1, got " + std::to_string(rings));
  }
  const double r = shape.sphere_radius(), d = shape.sphere_center_offset();
  const double alpha_max = std::asin(shape.half_width() / r);  // polar angle of the rim
  TriangleMesh mesh;
  auto& v = mesh.vertices;

  // Vertex layout: top pole, top rings 1..rings-1, rim, bottom rings rings-1..1, bottom pole.
  // Ring i (0 = top pole .. 2*rings = bottom pole) has `segments` vertices except the poles.
  const int ring_count = 2 * rings + 1;
  auto ring_start = [&](int i) { return i == 0 ? 0 : 1 + (i - 1) * segments; };
  for (int i = 0; i < ring_count; ++i) {
    const bool top = i <= rings;
    const int k = top ? i : 2 * rings - i;  // steps from the nearer pole
    const double alpha = alpha_max * k / rings;
    const double rho = r * std::sin(alpha);
    const double z = r * std::cos(alpha) - d;  // upper cap; the lower cap mirrors it
    if (k == 0) {
      v.emplace_back(0.0, 0.0, top ? z : -z);
      continue;
    }
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      v.emplace_back(rho * std::cos(phi), rho * std::sin(phi), top ? z : (k == rings ? 0.0 : -z));
    }
  }
  auto& tris = mesh.triangles;
  for (int i = 0; i + 1 < ring_count; ++i) {
    for (int j = 0; j < segments; ++j) {
      const int jn = (j + 1) % segments;
      if (i == 0) {  // fan around the top pole
        tris.push_back({0, ring_start(1) + j, ring_start(1) + jn});
      } else if (i + 1 == ring_count - 1) {  // fan around the bottom pole
        const int pole = ring_start(ring_count - 1);
        tris.push_back({ring_start(i) + j, pole, ring_start(i) + jn});
      } else {
        const int a = ring_start(i) + j, b = ring_start(i) + jn;
        const int c = ring_start(i + 1) + j, e = ring_start(i + 1) + jn;
        tris.push_back({a, c, e});
        tris.push_back({a, e, b});
      }
    }
  }
  return mesh;
}

}  // namespace virtual_go
