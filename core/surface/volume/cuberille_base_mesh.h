// A base mesh that follows an implicit surface's folds: the boundary of the coarse cells
// inside F < 0 (a "cuberille", G. Herman and H. K. Liu, "Three-dimensional display of human
// organs from computed tomograms", Computer Graphics and Image Processing 9(1), 1979), made
// manifold, its quads triangulated across a diagonal (a triangulated quadrangulation, as the
// 4-8 mesh needs; DESIGN.md, "The 4-8 mesh") and its vertices projected onto F = 0.
//
// Why not rays from a centre (make_projected_box_mesh): on a surface that is not star-shaped
// (a brain layer under the temporal lobe), neighbouring rays hit different sheets, the base
// edge between them spans the gap, and refinement never reaches the bottom of the fold: each
// split midpoint projects onto the nearer sheet, the gap-spanning edge never gets shorter
// than the gap, and the split queue grows without end. A cuberille's faces separate inside
// from outside cells, so every base edge lies within a cell of the surface on its own sheet.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct CuberilleOptions {
  double cell_size = 8.0;  // edge of the cubic cells, in the surface's units
};

struct CuberilleStats {
  std::size_t inside_cells = 0;
  std::size_t cells_added = 0;    // enclosed outside cells filled
  std::size_t split_corners = 0;  // extra vertices where inside cells touch at an edge or corner
  std::size_t quads = 0;
};

// The inside region is the largest face-connected component of cells whose centre has
// F < 0, with enclosed outside cells filled. Throws std::invalid_argument when no cell
// centre lies inside.
Mesh48 make_cuberille_base_mesh(const ImplicitSurface& surface, const Box3& box,
                                const CuberilleOptions& options = {},
                                CuberilleStats* stats = nullptr);

}  // namespace dynamesh
