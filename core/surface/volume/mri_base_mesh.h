// The first mesh of an mri layer (issue 16): every piece of the layer, cavities included, and
// embedded. The cuberille (cuberille_base_mesh.h) is embedded but keeps only the largest piece
// of its 8 mm cells and fills their cavities: Colin27 with closing 2 loses the surface of a
// 1.5 cm^3 cavity that opens to the outside 0.8 mm deep, and the local repair of that hole
// then has no inner sheet to stitch to. F's contour (contour_base_mesh.h) has every piece, but
// its projected triangles fold in the sulci (751 folded faces and 680 slivers on Colin27 at 8 mm
// against the cuberille's none; issue 16, session 13). So the cuberille is kept for the piece it
// has, and only the contour's other pieces are added: the cuberille has one piece, so a contour
// piece that none of its vertices is nearest to is one it lacks. Where the cuberille covers
// only part of its own contour piece (a neck thinner than its cells: it keeps one lobe of a
// dumbbell), the contour is taken whole: it is the only base with the whole layer.
#pragma once

#include <cstddef>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct MriBaseMeshOptions {
  double cell_size = 8.0;  // the cuberille's cells and the contour's grid spacing
  // A contour piece whose vertices are within one cell of the cuberille's vertices for less
  // than this fraction is not the cuberille's: the cuberille then misses part of the layer.
  double min_coverage = 0.9;
};

struct MriBaseMeshInfo {
  std::size_t contour_pieces = 0;   // 0: no contour (no crossing on its grid, or it failed)
  std::size_t pieces_added = 0;     // contour pieces added to the cuberille
  std::size_t votes_elsewhere = 0;  // cuberille vertices nearest to another piece (not added)
  double coverage = 1.0;            // of the cuberille's own contour piece
  bool contour_whole = false;       // the contour was taken instead of the cuberille
};

Mesh48 make_mri_base_mesh(const ImplicitSurface& surface, const MriBaseMeshOptions& options = {},
                          MriBaseMeshInfo* info = nullptr);

}  // namespace dynamesh
