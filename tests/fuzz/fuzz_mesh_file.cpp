// libFuzzer target: the base-mesh readers (core/surface/expression/triangle_mesh_file.h),
// PLY when the input starts with "ply", OBJ otherwise. A returned mesh must have valid
// indices and finite positions; bad input must end in std::invalid_argument.
#include <stdexcept>

#include "core/surface/expression/triangle_mesh_file.h"
#include "fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool ply = size >= 3 && data[0] == 'p' && data[1] == 'l' && data[2] == 'y';
  const std::string path = dynamesh::fuzz::input_file(data, size, ply ? ".ply" : ".obj");
  try {
    const dynamesh::TriangleMesh m = dynamesh::read_triangle_mesh(path);
    for (const auto& t : m.triangles)
      for (std::uint32_t i : t)
        if (i >= m.positions.size()) __builtin_trap();
    for (const auto& p : m.positions)
      if (!p.allFinite()) __builtin_trap();
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
