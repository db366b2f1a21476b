// Marching tetrahedra: the zero set of a scalar field sampled on a grid, as a closed,
// consistently oriented triangle mesh of any genus and any number of components (issue 16,
// "initial meshes from F"). Each grid cube is cut into the six tetrahedra of its Kuhn
// triangulation around the diagonal (0,0,0)-(1,1,1); that triangulation is the same in every
// cube, so neighbouring cubes agree on their shared faces. With the binary sign inside = F < 0
// a tetrahedron holds no surface, one triangle (one or three corners inside) or one quad (two
// inside, cut into two triangles), and the surface is the level set of the piecewise-linear
// interpolant: a 2-manifold without boundary wherever the grid's sides are all outside. No
// case table is ambiguous (unlike marching cubes), which is why tetrahedra are used here.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct ContourGrid {
  Box3 box;                           // the grid spans it, corners included
  std::array<int, 3> cells{1, 1, 1};  // cubes along each axis
  Vec3 spacing() const;
  Vec3 point(int i, int j, int k) const;
};

// The contour of a triangle mesh with vertices on grid edges (before any projection).
struct ContourMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  // The grid edge each vertex lies on: its inside end (F < 0) and outside end.
  std::vector<std::array<Vec3, 2>> edges;
};

// Cells of about `spacing` over `box`, at least 2 along each axis.
ContourGrid make_contour_grid(const Box3& box, double spacing);

// F sampled at every grid point (x fastest); serial, like sample_field (critical_points.h).
std::vector<double> sample_grid(const ImplicitSurface& surface, const ContourGrid& grid);

// The zero set of the sampled values (size (cells+1)^3, x fastest). A crossing is placed by
// linear interpolation, kept at least `margin` (a fraction of the edge) from either end so that
// no triangle is degenerate before projection. Throws std::invalid_argument when F < 0 at a
// grid point on the box's sides (the contour would be open there), unless `open` is set: a
// local contour (the local repair's patch) may end at the box's sides.
ContourMesh marching_tetrahedra(const ContourGrid& grid, const std::vector<double>& values,
                                double margin = 0.05, bool open = false);

// The zero of F on a contour vertex's grid edge (inside, outside), by regula falsi with the
// Illinois fix, kept at least `margin` (a fraction of the edge) from either end: a point of
// the surface that belongs to this edge, unlike one found by Newton steps, which near a
// critical point of F may run off to another sheet. With a `level`: the root of F - level.
Vec3 root_on_edge(const ImplicitSurface& surface, const std::array<Vec3, 2>& edge, double margin,
                  double level = 0.0);

}  // namespace dynamesh
