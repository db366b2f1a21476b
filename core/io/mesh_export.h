// Export of a mesh snapshot to PLY (binary little-endian or ASCII) and Wavefront OBJ.
// Per-vertex scalar fields become float vertex properties in PLY; OBJ has no place for
// them, so the first field (if any) is written as a 1-D texture coordinate `vt s` per vertex
// and every field's name is listed in a header comment.
// Files are written to a temporary name and renamed when complete, so a failed export never
// leaves a partial file that looks complete. Errors throw std::runtime_error naming the file.
#pragma once

#include <string>

#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

enum class PlyFormat { kBinary, kAscii };

void write_ply(const std::string& path, const MeshSnapshot& mesh,
               PlyFormat format = PlyFormat::kBinary);
void write_obj(const std::string& path, const MeshSnapshot& mesh);
// By extension: .ply (binary) or .obj; throws std::invalid_argument for any other.
void write_mesh(const std::string& path, const MeshSnapshot& mesh);

}  // namespace dynamesh
