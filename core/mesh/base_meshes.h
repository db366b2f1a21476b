// Base meshes: triangulated quadrangulations from which every adapted mesh is refined
// (DESIGN.md, "The 4-8 mesh"). Each quad is split along a diagonal that becomes the
// refinement edge of both its triangles; diagonals alternate in a checkerboard so that
// uniform refinement produces the regular 4-8 pattern (valences 4 and 8).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {

// Open rectangle of nx * ny quads over [uv_min, uv_max]. Vertices get uv = (u, v) and
// position (u, 0, v), the layout of a height field y = f(x, z) before evaluation.
Mesh48 make_grid_mesh(int nx, int ny, const Vec2& uv_min, const Vec2& uv_max);

// Closed box of quads (sphere topology) on the surface of `box`, with counts[i] quads along
// axis i. Outward-facing (counter-clockwise seen from outside). uv is unused (zero).
Mesh48 make_box_mesh(const Box3& box, const std::array<int, 3>& counts);

// Any manifold triangle mesh, open or closed, made 4-8 by Velho's construction: triangles
// are paired greedily across their longest shared edges and each pair is split into four
// around the edge midpoint; each unpaired triangle is split into three at its centroid.
// Every original edge is then a quad diagonal. `uvs` may be empty (then zero).
// Throws std::invalid_argument for non-manifold or inconsistently oriented input.
Mesh48 make_48_mesh(const std::vector<Vec3>& positions, const std::vector<Vec2>& uvs,
                    const std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace dynamesh
