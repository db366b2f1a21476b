// Local repair of a topology change (issue 16, item 3): instead of rebuilding the whole mesh,
// cut out the faces near the event's critical point, contour F there on a fine local grid,
// stitch the contour to the hole's border and pair the new triangles into base diamonds; the
// adapter's queues then refine and coarsen the new region as they do everywhere. Vertices
// away from the event keep their ids (and so their history).
//
//  1. Cut: every face with a vertex within `radius` of the event, closed so that no remaining
//     face has its refinement edge on the border (the new faces are base faces, depth 0, and a
//     refinement edge must be shared or lead to a coarser face, Mesh48::check), and grown by
//     one face that is not a diamond's (splitting a diamond to make one if need be) wherever
//     a border loop has an odd number of edges: the new triangles beyond a loop number as
//     many as its edges, modulo 2, and a perfect matching needs an even count.
//  2. Patch: marching tetrahedra of F on a grid of `spacing` around the event (a grid point on
//     the event itself, so that a neck thinner than the grid is not missed), the triangles
//     with all corners within radius - spacing / 2, their corners on F (root on their grid
//     edge, then Newton).
//  3. Stitch: each border loop is zipped to the patch loop nearest to it (centroids) by a
//     strip of triangles, the shorter rung first (the classic contour-stitching greedy).
//  4. Pair: a perfect matching of the new triangles (triangle_pairing.h); each pair's shared
//     edge is their refinement edge. A disk's triangles often have none: the maximum
//     matching is mended by edge flips and splits along dual paths between the single
//     triangles (pair_triangles_mending). Loops that do not correspond, a pinched border, a
//     mend that would turn a triangle over: no repair (the caller falls back to a global
//     re-base).
#pragma once

#include <string>
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct LocalRepairOptions {
  double radius = 0.0;   // faces with a vertex this close to the event are cut out
  double spacing = 0.0;  // of the local contour grid: the finest
  // The coarsest: the contour's spacing follows the seam's edges (as fine as the queues made
  // them for T there) between `spacing` and this, so the new faces are no finer than the
  // faces around them and the queues re-adapt the region both ways.
  double max_spacing = 0.0;
  // The work bound: the cells of the patches' contour grids, summed over the attempts (each
  // costs one evaluation of F per grid point). An attempt that would pass it is not made. The
  // analytic scenes' repairs take at most ~40,000 per attempt; a patch's grid has at most
  // (2 (r / h + 2))^3 cells, r / h at most 24 in the ladder of repair_locally.
  std::size_t max_grid_cells = std::size_t{1} << 22;
};

struct LocalRepairResult {
  bool repaired = false;
  std::string why_not;  // when not repaired
  std::size_t removed_faces = 0;
  std::size_t added_faces = 0;
  double spacing = 0.0;                       // the patch's contour spacing
  int pairing_flips = 0, pairing_splits = 0;  // that mended the new triangles' matching
  std::size_t grid_cells = 0;                 // of the patch's contour grid
  std::vector<Vertex> new_vertices;
};

// Leaves the mesh unchanged unless it returns repaired: each attempt works on a copy, and only
// the one that succeeds is made on the mesh (its 4-8 splits, which level the cut's border or
// mend the parity of a border loop, told to the mesh's listeners; then the surgery).
LocalRepairResult repair_locally(Mesh48& mesh, const ImplicitSurface& surface, const Vec3& centre,
                                 const LocalRepairOptions& options);

}  // namespace dynamesh
