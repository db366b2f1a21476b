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
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"
#include "core/topology/critical_points.h"

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

// The depth, at most `depth`, at which to start a layer's first mesh (Surface::mild_time): the
// deepest one no critical point of the distance D (`points`, value = D there) lies within half
// a cell of, else 0 (the mask's own boundary, where the base is built as the cavity's and
// lobes' pieces allow: mri_base_mesh.h above). The layers move at unit speed (|grad D| = 1), so
// a hole, neck, wall or lobe born or vanishing at a critical point is narrower than a cell
// within half a cell of its depth, and the base's 8 mm cells do not resolve it: Colin27 with
// closing 2 started 1 or 2 mm deep, past the hole that opens into a cavity 0.81 mm deep, had a
// base with the cavity covered over; its refinement ran into the triangle budget with 24-28 mm
// of error where split vertices projected through the hole. From the depth given here the
// adapter reaches `depth` by motion, and events on the way are repaired as in any run.
double mri_start_depth(const std::vector<CriticalPoint>& points, double depth,
                       const MriBaseMeshOptions& options = {});

}  // namespace dynamesh
