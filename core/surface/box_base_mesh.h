// Base meshes of the closed implicit scenes (DESIGN.md, "The 4-8 mesh"): a box of quads
// (make_box_mesh) whose vertices are moved onto the surface, first by a scene-specific
// placement (e.g. the nearest point of the rest shape, then the deformation), then polished by
// Newton projection so that every base vertex satisfies |F| within tolerance.
#pragma once

#include <array>
#include <functional>

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

// `place` maps a vertex of the box to (near) its point on the surface; it must preserve
// orientation so that the faces stay outward. Throws std::logic_error if a placed vertex cannot
// be projected (a bug in the scene, not a user error).
Mesh48 make_projected_box_mesh(const ImplicitSurface& surface, const Box3& box,
                               const std::array<int, 3>& counts,
                               const std::function<Vec3(const Vec3&)>& place);

}  // namespace dynamesh
