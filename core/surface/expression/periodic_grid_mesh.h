// A grid base mesh whose periodic directions close up: along a periodic u the last column of
// vertices *is* the first (not a copy), so the mesh has no boundary there and the adapter's
// seam handling (ParametricSurface::unwrap_near / wrap_into_domain) interpolates across it.
// u periodic gives a cylinder (boundary only at v = min and v = max), u and v a torus.
// (This belongs with make_grid_mesh in core/mesh/base_meshes.h; it lives here until then.)
#pragma once

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {

// nx * ny quads over [uv_min, uv_max], each split along a checkerboard diagonal as
// make_grid_mesh does. Vertices get their uv (in [min, max) along periodic directions) and
// position (u, 0, v); counter-clockwise in (u, v). A periodic direction needs an even count
// of at least 4 (so that no triangle repeats a vertex and the checkerboard continues across
// the seam); throws std::invalid_argument otherwise.
Mesh48 make_periodic_grid_mesh(int nx, int ny, const Vec2& uv_min, const Vec2& uv_max,
                               bool periodic_u, bool periodic_v);

}  // namespace dynamesh
