// The mesh file behind ~marker: the binary STL is read back here with an independent reader and
// checked against the lens itself (vertices on its two spherical faces, outward normals, the
// enclosed volume against the closed form), and the file is written whole or not at all.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/geometry/tessellation.h"
#include "virtual_go/sim/mesh_file.h"

namespace vg = virtual_go;
namespace fs = std::filesystem;

namespace {

using Vec = std::array<double, 3>;
struct Facet {
  Vec normal;
  std::array<Vec, 3> vertex;
};

// Binary STL, read as its definition says: little-endian, whatever this machine is.
std::uint32_t u32_at(const std::string& bytes, std::size_t pos) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes.at(pos + i));
  return v;
}

double f32_at(const std::string& bytes, std::size_t pos) {
  const std::uint32_t bits = u32_at(bytes, pos);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::vector<Facet> read_stl(const std::string& bytes) {
  const std::uint32_t n = u32_at(bytes, 80);
  EXPECT_EQ(bytes.size(), 84u + 50u * n);
  std::vector<Facet> facets(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::size_t base = 84 + 50 * static_cast<std::size_t>(t);
    for (int k = 0; k < 3; ++k) facets[t].normal[k] = f32_at(bytes, base + 4 * k);
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 3; ++k)
        facets[t].vertex[v][k] = f32_at(bytes, base + 12 * (v + 1) + 4 * k);
    }
    EXPECT_EQ(bytes[base + 48], 0);
    EXPECT_EQ(bytes[base + 49], 0);
  }
  return facets;
}

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("vg_mesh_file_" + name + "_" +
                        std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST(MeshFile, BinaryStlHoldsTheLens) {
  // Size 33: w 22 mm, h 9.2 mm; the lens written here from its definition (DESIGN: a = w / 2,
  // c = h / 2, sphere radius R = (a^2 + c^2) / 2c, centres at -/+ (R - c)).
  const double a = 0.011, c = 0.0046, r = (a * a + c * c) / (2 * c);
  const vg::LensShape shape(2 * a, 2 * c);
  const vg::TriangleMesh mesh = vg::tessellate_lens(shape, 64, 8);
  const std::string stl = vg::binary_stl(mesh);

  ASSERT_GE(stl.size(), 84u);
  EXPECT_NE(stl.compare(0, 5, "solid"), 0) << "a binary STL must not look like an ASCII one";
  const std::vector<Facet> facets = read_stl(stl);
  ASSERT_EQ(facets.size(), mesh.triangles.size());

  double six_volume = 0.0, worst_surface = 0.0;
  for (const Facet& f : facets) {
    for (const Vec& p : f.vertex) {
      const double rho = std::hypot(p[0], p[1]);
      EXPECT_LE(rho, a + 1e-8);
      const double z_surface = std::sqrt(std::max(0.0, r * r - rho * rho)) - (r - c);
      worst_surface = std::max(worst_surface, std::abs(std::abs(p[2]) - z_surface));
    }
    const Vec n = f.normal;
    EXPECT_NEAR(std::sqrt(dot(n, n)), 1.0, 1e-6);
    const Vec winding = cross(sub(f.vertex[1], f.vertex[0]), sub(f.vertex[2], f.vertex[0]));
    EXPECT_GT(dot(n, winding), 0.0) << "normal against the vertex order";
    const Vec centroid = {(f.vertex[0][0] + f.vertex[1][0] + f.vertex[2][0]) / 3,
                          (f.vertex[0][1] + f.vertex[1][1] + f.vertex[2][1]) / 3,
                          (f.vertex[0][2] + f.vertex[1][2] + f.vertex[2][2]) / 3};
    EXPECT_GT(dot(n, centroid), 0.0) << "normal points inwards";  // convex, origin inside
    six_volume += dot(f.vertex[0], cross(f.vertex[1], f.vertex[2]));
  }
  // float32 metres: a vertex moves by at most about 1e-9 m.
  EXPECT_LT(worst_surface, 1e-8);
  // The polyhedron inscribed in the lens: a little smaller than the lens, by the tessellation
  // error only (the float rounding is far below it).
  const double lens_volume = M_PI * c * (3 * a * a + c * c) / 3;
  const double volume = six_volume / 6;
  EXPECT_LT(volume, lens_volume);
  EXPECT_GT(volume, 0.99 * lens_volume);
}

TEST(MeshFile, NameChangesWithTheContent) {
  const vg::LensShape size33(0.022, 0.0092), size22(0.022, 0.0063);
  const std::string stl33 = vg::binary_stl(vg::tessellate_lens(size33, 64, 8));
  const std::string stl22 = vg::binary_stl(vg::tessellate_lens(size22, 64, 8));
  const std::string name = vg::mesh_file_name(size33, stl33);
  EXPECT_EQ(name.rfind("lens_22x9.2mm_", 0), 0u) << name;
  EXPECT_EQ(name.substr(name.size() - 4), ".stl");
  EXPECT_EQ(vg::mesh_file_name(size33, stl33), name) << "same content, same name";
  EXPECT_NE(vg::mesh_file_name(size22, stl22), name);
  std::string changed = stl33;
  changed[100] ^= 1;  // one bit of one vertex
  EXPECT_NE(vg::mesh_file_name(size33, changed), name) << "rviz would keep the old mesh";
}

TEST(MeshFile, WritesTheWholeFileAndNothingElse) {
  const fs::path dir = scratch("write") / "nested" / "folder";
  const std::string bytes = vg::binary_stl(vg::tessellate_lens(vg::LensShape(0.022, 0.0092), 8, 2));
  const std::string path = vg::write_mesh_file(dir.string(), "lens.stl", bytes);
  EXPECT_TRUE(fs::path(path).is_absolute());
  EXPECT_EQ(fs::path(path), fs::absolute(dir / "lens.stl"));
  EXPECT_EQ(read_file(path), bytes);
  // Again, over the existing file (another node with the same stone).
  EXPECT_EQ(vg::write_mesh_file(dir.string(), "lens.stl", bytes), path);
  EXPECT_EQ(read_file(path), bytes);
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename());
  EXPECT_EQ(files, std::vector<std::string>{"lens.stl"}) << "a temporary file was left behind";
  fs::remove_all(scratch("write"));
}

TEST(MeshFile, UnwritableFolderIsAnErrorNamingIt) {
  const fs::path base = scratch("unwritable");
  fs::create_directories(base);
  const fs::path blocker = base / "a_file";
  std::ofstream(blocker) << "not a folder";
  const std::string dir = (blocker / "meshes").string();
  try {
    vg::write_mesh_file(dir, "lens.stl", "x");
    ADD_FAILURE() << "wrote below a regular file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos) << e.what();
  }
  fs::remove_all(base);
}
