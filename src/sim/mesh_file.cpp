#include "virtual_go/sim/mesh_file.h"

#include <unistd.h>

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace virtual_go {
namespace {

// Little-endian whatever the host's byte order (STL is little-endian by definition).
void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

void put_f32(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put_u32(out, bits);
}

void put_vector(std::string& out, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) put_f32(out, v[i]);
}

// FNV-1a, 64 bit: a content fingerprint for the file name, not a security hash.
std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string binary_stl(const TriangleMesh& mesh) {
  std::string out;
  out.reserve(84 + 50 * mesh.triangles.size());
  // The header must not start with "solid": some readers take that for an ASCII STL.
  std::string header = "virtual_go lens, metres, body frame (z = symmetry axis)";
  header.resize(80, ' ');
  out += header;
  put_u32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    put_vector(out, (b - a).cross(c - a).normalized());  // counter-clockwise: outward
    put_vector(out, a);
    put_vector(out, b);
    put_vector(out, c);
    out.push_back(0);  // attribute byte count
    out.push_back(0);
  }
  return out;
}

std::string mesh_file_name(const LensShape& shape, const std::string& stl) {
  char name[96];
  std::snprintf(name, sizeof name, "lens_%.6gx%.6gmm_%016llx.stl", shape.width() * 1e3,
                shape.height() * 1e3, static_cast<unsigned long long>(fnv1a(stl)));
  return name;
}

std::string write_mesh_file(const std::string& dir, const std::string& name,
                            const std::string& bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path folder = fs::absolute(dir, ec);
  if (ec) throw std::runtime_error("mesh folder " + dir + ": " + ec.message());
  const fs::path path = folder / name;
  fs::create_directories(folder, ec);
  if (ec) throw std::runtime_error("cannot create " + folder.string() + ": " + ec.message());
  // Unique per process, so two nodes writing the same mesh at once do not share a temporary.
  const fs::path tmp = folder / (name + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      const std::string reason = std::strerror(errno);
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write " + tmp.string() + ": " + reason);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " +
                             reason);
  }
  return path.string();
}

}  // namespace virtual_go
