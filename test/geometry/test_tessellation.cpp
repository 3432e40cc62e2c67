// Tessellation of the lens: a closed, consistently outward-oriented triangle mesh whose vertices
// lie on the two spherical faces and whose enclosed volume converges to the lens volume.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "support/physics_reference.h"
#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/geometry/tessellation.h"

namespace vg = virtual_go;

namespace {

// Divergence theorem, written here: sum of signed tetrahedra from the origin.
double mesh_volume(const vg::TriangleMesh& mesh) {
  double six = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]],
                          &c = mesh.vertices[t[2]];
    six += a.x() * (b.y() * c.z() - b.z() * c.y()) - a.y() * (b.x() * c.z() - b.z() * c.x()) +
           a.z() * (b.x() * c.y() - b.y() * c.x());
  }
  return six / 6.0;
}

double lens_volume(double a, double c) { return M_PI * c * (3 * a * a + c * c) / 3; }

}  // namespace

TEST(Tessellation, MeshIsClosedAndConsistentlyOriented) {
  const vg::LensShape shape(0.022, 0.0092);
  for (const auto& [segments, rings] :
       std::vector<std::pair<int, int>>{{3, 1}, {4, 2}, {7, 3}, {32, 8}}) {
    SCOPED_TRACE(std::to_string(segments) + " segments, " + std::to_string(rings) + " rings");
    const vg::TriangleMesh mesh = vg::tessellate_lens(shape, segments, rings);
    const int nv = static_cast<int>(mesh.vertices.size());
    // Each directed edge exactly once, and its reverse exactly once: every edge is shared by
    // exactly two triangles that traverse it in opposite directions.
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(t[k], 0);
        ASSERT_LT(t[k], nv);
        ++directed[{t[k], t[(k + 1) % 3]}];
      }
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1) << edge.first << "->" << edge.second;
      const auto reverse = directed.find({edge.second, edge.first});
      ASSERT_NE(reverse, directed.end()) << "open edge " << edge.first << "-" << edge.second;
      EXPECT_EQ(reverse->second, 1);
    }
    // A closed genus-0 surface: V - E + F = 2.
    const int edges = static_cast<int>(directed.size()) / 2;
    EXPECT_EQ(nv - edges + static_cast<int>(mesh.triangles.size()), 2);
    // Every vertex is used; no degenerate triangle; normals point away from the (convex)
    // lens's centre.
    std::set<int> used;
    for (const auto& t : mesh.triangles) {
      used.insert(t.begin(), t.end());
      const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]],
                            &c = mesh.vertices[t[2]];
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      EXPECT_GT(normal.norm(), 1e-14);
      EXPECT_GT(normal.dot((a + b + c) / 3.0), 0.0);
    }
    EXPECT_EQ(static_cast<int>(used.size()), nv);
  }
}

TEST(Tessellation, VerticesLieOnTheSphericalFaces) {
  const double a = 0.011, c = 0.0046;
  const double d = (a * a - c * c) / (2 * c), r = c + d;  // face spheres at -/+ d, radius r
  const vg::TriangleMesh mesh = vg::tessellate_lens(vg::LensShape(2 * a, 2 * c), 24, 6);
  bool top_pole = false, bottom_pole = false;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    const Eigen::Vector3d centre(0, 0, v.z() >= 0 ? -d : d);
    EXPECT_NEAR((v - centre).norm(), r, 1e-15);
    EXPECT_LE(std::abs(v.z()), c + 1e-16);
    top_pole |= std::abs(v.z() - c) < 1e-16;
    bottom_pole |= std::abs(v.z() + c) < 1e-16;
  }
  EXPECT_TRUE(top_pole);
  EXPECT_TRUE(bottom_pole);
}

TEST(Tessellation, EnclosedVolumeConvergesToTheLensVolumeAtSecondOrder) {
  // An inscribed polyhedron of a smooth convex surface misses a volume O(h^2) in the edge length.
  const double a = 0.011, c = 0.0046;
  const vg::LensShape shape(2 * a, 2 * c);
  const double exact = lens_volume(a, c);
  std::vector<double> hs, errors;
  for (int k = 1; k <= 32; k *= 2) {
    const vg::TriangleMesh mesh = vg::tessellate_lens(shape, 8 * k, 2 * k);
    const double v = mesh_volume(mesh);
    EXPECT_NEAR(mesh.enclosed_volume(), v, 1e-15 * exact);
    EXPECT_LT(v, exact);  // inscribed in a convex body
    hs.push_back(1.0 / k);
    errors.push_back((exact - v) / exact);
  }
  const double order = vgtest::fitted_order(hs, errors);
  std::printf("tessellation volume: relative error %.3e (8x2) ... %.3e (256x64), order %.3f\n",
              errors.front(), errors.back(), order);
  EXPECT_NEAR(order, 2.0, 0.1);
  EXPECT_LT(errors.back(), 1e-3);
}
