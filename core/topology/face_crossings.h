// Whether new faces cross the rest of a mesh (issue 16): a guard on a local re-mesh. A patch
// stitched into a neck thinner than its grid can pass through the mesh's other sheet while
// every new face still faces up grad F; such a mesh is not embedded, and the caller falls back
// to a global re-base. Floating-point (not exact) predicates: a guard, not a judge (the tests
// judge with CGAL, tests/support/mesh_validity.h).
#pragma once

#include <vector>

#include "core/mesh/mesh48.h"

namespace dynamesh {

// Pairs (f, g), f in `faces`, g any live face sharing no vertex with f, whose triangles cross:
// an edge of one passes through the other's interior. Counting stops at `enough`.
std::size_t count_face_crossings(const Mesh48& mesh, const std::vector<Face>& faces,
                                 std::size_t enough = 1);

}  // namespace dynamesh
