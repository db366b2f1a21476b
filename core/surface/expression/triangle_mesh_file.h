// Reading a triangle mesh from a file, for user-supplied base meshes (--base-mesh): Wavefront
// OBJ (v and f statements) and PLY (ascii or binary little/big endian; vertex x, y, z of any
// numeric type; faces as a list property "vertex_indices" or "vertex_index"; other elements
// and properties are skipped), both by small strict readers: a malformed or truncated line,
// a face with fewer than three corners, a PLY count larger than the file can hold or smaller
// than its data is an error, never a partial mesh. Polygons with more than three corners are
// fanned into triangles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// By extension (.obj or .ply, any case). Throws std::invalid_argument, one line with the file
// name and what is wrong: missing or unreadable file, unknown extension, malformed content,
// index out of range, non-finite coordinate, no triangles.
TriangleMesh read_triangle_mesh(const std::string& path);

}  // namespace dynamesh
