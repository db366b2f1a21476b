// Local repair of the two events that make or remove a whole component of the surface (issue
// 16): a minimum of F crossing zero downwards gives birth to a blob, a maximum crossing upwards
// to a bubble of outside within the solid; crossing back, they die. Neither touches the rest of
// the mesh, so neither needs the cut, contour and stitch of repair_locally (local_repair.h),
// which refuses them ("nothing to cut near the event"): a birth adds a closed component
// contoured around the critical point, a death removes the small component around it. Every
// other vertex keeps its identity, where a global re-base would keep none.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"
#include "core/topology/local_repair.h"

namespace dynamesh {

// Adds the component of F's zero set around `centre` (a minimum of F below zero, or a maximum
// above it), contoured by marching tetrahedra on a grid of `options.spacing` that has a node at
// the centre, growing the grid until the region of F's sign at the centre, flood-filled from
// there, is enclosed by it. Refused, the mesh unchanged, when the region reaches past
// `options.radius` * 4, when the mesh has a vertex in its box (the component is not new), or
// when its contour is not one sphere.
LocalRepairResult add_born_component(Mesh48& mesh, const ImplicitSurface& surface,
                                     const Vec3& centre, const LocalRepairOptions& options);

// Removes the component of the mesh nearest to `centre` when all of its vertices are within
// `options.radius` of it and F no longer has its sign there (the blob or bubble is gone).
// Refused, the mesh unchanged, otherwise.
LocalRepairResult remove_dead_component(Mesh48& mesh, const ImplicitSurface& surface,
                                        const Vec3& centre, const LocalRepairOptions& options);

}  // namespace dynamesh
