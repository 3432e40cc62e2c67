// The stone's display mesh as a binary STL file, for rviz's MESH_RESOURCE marker. ROS-free.
//
// Why a file: rviz drops a marker for good when it arrives before the first transform of its
// frame (tf2 fails a stamp-0 request once that frame appears; ros-visualization/rviz#494), so
// the node republishes its marker once a second. A TRIANGLE_LIST of the lens is 138 KB per
// message; a MESH_RESOURCE marker that names this file is a few hundred bytes.
#pragma once

#include <cstdint>
#include <string>

#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/geometry/tessellation.h"

namespace virtual_go {

// Binary STL (80-byte header, little-endian uint32 count, then per triangle a float32 unit
// normal, three float32 vertices and a uint16 0), in metres, in the mesh's own frame.
std::string binary_stl(const TriangleMesh& mesh);

// A name that changes with the content ("lens_22x9.2mm_<16 hex digits>.stl"): rviz caches a
// mesh by its URI, so a stone of another size must not reuse the name of an older file.
std::string mesh_file_name(const LensShape& shape, const std::string& stl);

// Writes `bytes` to dir/name atomically (a temporary file renamed over it, so a reader such as
// rviz never sees half a file), creating dir. Returns the absolute path. Throws
// std::runtime_error naming the path and the reason.
std::string write_mesh_file(const std::string& dir, const std::string& name,
                            const std::string& bytes);

}  // namespace virtual_go
