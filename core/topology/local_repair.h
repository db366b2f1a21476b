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
//     many as its edges, modulo 2, and a perfect matching needs an even count. Where the
//     faces near the event are coarse against the radius (a brain layer's, up to 10 mm
//     across), an attempt first splits them until none within `radius` has an edge longer
//     than radius / 2, so that the cut stays near the event. A patch whose new triangles
//     stray from F by more than its spacing is refused.
//  2. Patch: marching tetrahedra of F on a grid of `spacing` around the event (a grid point on
//     the event itself, so that a neck thinner than the grid is not missed), the triangles
//     with all corners within radius - spacing / 2, their corners on F (root on their grid
//     edge, then Newton). At an event's instant, F = L off zero (contour_level).
//  3. Stitch: each border loop is zipped to the patch loop nearest to it (centroids) by a
//     strip of triangles, the shorter rung first (the classic contour-stitching greedy).
//  4. Pair: a perfect matching of the new triangles (triangle_pairing.h); each pair's shared
//     edge is their refinement edge. A disk's triangles often have none: the maximum
//     matching is mended by edge flips and splits along dual paths between the single
//     triangles (pair_triangles_mending). Loops that do not correspond, a pinched border, a
//     mend that would turn a triangle over: no repair (the caller falls back to a global
//     re-base).
#pragma once

#include <functional>
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
  // The work bound: the cells of the patches' contour grids, summed over the attempts at one
  // level (each costs one evaluation of F per grid point). An attempt that would pass it is not
  // made. The analytic scenes' repairs take at most ~40,000 per attempt; a patch's grid has at
  // most (2 (r / h + 2))^3 cells, r / h at most 24 in the ladder of repair_locally.
  std::size_t max_grid_cells = std::size_t{1} << 22;
  // Where a 4-8 split puts its new vertex, called as a listener's after_split is (the vertex at
  // its parents' midpoint). The attempts split a copy of the mesh that tells no listener and
  // plan the cut, the patch and the seam on the positions this gives; the successful attempt's
  // splits are then made on the mesh itself, where its listeners place the vertices. A caller
  // whose mesh has such a listener gives its rule here (the adapter: its probe's
  // put_split_vertex), so that the mesh gets every vertex where the plan had it, bit for
  // bit; a repair whose replayed splits land elsewhere is refused before its surgery. Empty:
  // split_point_on_surface, and the repair puts the replayed vertices there itself (a mesh
  // nobody listens to).
  std::function<void(Mesh48&, const DiamondChange&)> place_split_vertex;
  // The level L of the patch's contour, F = L, on a grid over `box` of cell diagonal
  // `diagonal` (its vertices then projected onto F = 0, as far as they may go). Empty: 0. Right
  // at an event's instant F's critical point is zero to within rounding and the patch's grid,
  // which has a point on it, cannot resolve its side: a caller that knows F's critical points
  // gives L off zero just far enough that each in the box keeps its side
  // (TopologyMonitor::clear_level). The attempts at F = L follow those at F = 0, where none of
  // those would do and L is not 0 near the event.
  std::function<double(const Box3& box, double diagonal)> contour_level;
  // Each rung also tries its cuts with the patch filling the whole cut (HoleFill), after the
  // three usual modes. For a layer of a distance field, whose faces at a cavity's rim stretch to
  // 2-7 mm. Off elsewhere: on a surface no mesh can follow (CliHostile's ripple, hundreds of
  // folds) the fills made each failing ladder dearer, 7 s of CPU before the refusal became 95 s.
  bool fill_cut = false;
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
  // Every vertex slot's position on the successful attempt's copy after its surgery: what the
  // plan was made for, and what the mesh now holds (tests compare the two).
  std::vector<Vec3> planned_positions;
};

// Where a split of the edge ab puts its new vertex when LocalRepairOptions::place_split_vertex
// is empty: the midpoint projected onto F, or left at the midpoint where Newton does not
// converge or lands farther than half the edge away (on another part of F).
Vec3 split_point_on_surface(const ImplicitSurface& surface, const Vec3& a, const Vec3& b);

// Leaves the mesh unchanged unless it returns repaired: each attempt works on a copy, and only
// the one that succeeds is made on the mesh (its 4-8 splits, which level the cut's border or
// mend the parity of a border loop, told to the mesh's listeners; then the surgery). Should
// the replayed splits not give the copy's vertices (ids, or positions: a place_split_vertex
// that is not the listeners' rule), the repair is refused with the splits made.
LocalRepairResult repair_locally(Mesh48& mesh, const ImplicitSurface& surface, const Vec3& centre,
                                 const LocalRepairOptions& options);

}  // namespace dynamesh
