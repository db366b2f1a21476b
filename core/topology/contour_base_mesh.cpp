#include "core/topology/contour_base_mesh.h"

#include <algorithm>
#include <stdexcept>

#include "core/geometry/tangential_smoothing.h"
#include "core/mesh/base_meshes.h"
#include "core/surface/projection.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/triangle_pairing.h"

namespace dynamesh {

namespace {

using Triangle = std::array<std::uint32_t, 3>;

// Local index i of f's edge (f[i+1], f[i+2]) that g has reversed.
int shared_edge(const Triangle& f, const Triangle& g) {
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t a = f[(i + 1) % 3], b = f[(i + 2) % 3];
    for (int j = 0; j < 3; ++j)
      if (g[j] == b && g[(j + 1) % 3] == a) return i;
  }
  return -1;
}

// Each pair's shared edge becomes the refinement edge of both: (apex, a, b) with (a, b) shared.
Mesh48 paired_mesh(std::vector<Vec3> positions, const std::vector<Triangle>& triangles,
                   const std::vector<std::int64_t>& partner) {
  std::vector<Triangle> rotated(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const int i = shared_edge(t, triangles[static_cast<std::size_t>(partner[f])]);
    if (i < 0) throw std::logic_error("contour: paired triangles share no edge");
    rotated[f] = {t[i], t[(i + 1) % 3], t[(i + 2) % 3]};
  }
  return Mesh48::from_base_triangles(std::move(positions), {}, rotated);
}

// The zero of F on the grid edge (inside, outside), by regula falsi with the Illinois fix, kept
// at least `margin` from either end: a point of the surface that belongs to this edge, unlike
// one found by Newton steps, which near a critical point of F may run off to another sheet.
Vec3 edge_root(const ImplicitSurface& surface, const std::array<Vec3, 2>& edge, double margin) {
  double a = 0.0, b = 1.0;
  double fa = surface.value(edge[0]), fb = surface.value(edge[1]);
  int side = 0;
  for (int i = 0; i < 40 && fa < 0 && fb >= 0; ++i) {
    const double s = (a * fb - b * fa) / (fb - fa);
    const double fs = surface.value((1 - s) * edge[0] + s * edge[1]);
    if (fs < 0) {
      a = s, fa = fs;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = s, fb = fs;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
    if (b - a < 1e-12) break;
  }
  const double s = std::clamp(0.5 * (a + b), margin, 1.0 - margin);
  return (1 - s) * edge[0] + s * edge[1];
}

}  // namespace

Mesh48 make_contour_base_mesh(const ImplicitSurface& surface, const ContourBaseOptions& options,
                              ContourBaseInfo* info) {
  const Box3 box = surface.bounds();
  const double spacing = options.spacing > 0
                             ? options.spacing
                             : box.size().maxCoeff() / std::max(2, options.cells_along_longest);
  const ContourGrid grid = make_contour_grid(box, spacing);
  const ContourMesh contour = marching_tetrahedra(grid, sample_grid(surface, grid));
  if (contour.triangles.empty())
    throw std::invalid_argument(surface.name() + ": F has no zero crossing on a grid of spacing " +
                                std::to_string(spacing) + " over the bounds");
  std::vector<Vec3> positions = contour.positions;
  constexpr double kMargin = 0.05;
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = edge_root(surface, contour.edges[i], kMargin);
  const std::vector<std::int64_t> partner = pair_triangles(positions, contour.triangles);
  std::size_t unpaired = 0;
  for (const std::int64_t p : partner) unpaired += p < 0;
  Mesh48 mesh = unpaired == 0 ? paired_mesh(positions, contour.triangles, partner)
                              : make_48_mesh(positions, {}, contour.triangles);
  // Newton polishes what the margin moved off the surface (and places the midpoints Velho's
  // construction adds). A vertex that does not converge, or would travel more than a tenth
  // of a cell (near a point where grad F = 0 on the surface, as at the instant of a pinch, the
  // gradient flow leads away to the other sheet), keeps its place on its grid edge, within a
  // tenth of a cell of the surface; the adapter's normal correction tries again every step.
  std::size_t failures = 0;
  for (const Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(surface, mesh.position(v));
    if (r.converged && (r.point - mesh.position(v)).norm() <= 0.1 * spacing)
      mesh.position(v) = r.point;
    else
      ++failures;
  }
  if (failures == mesh.n_vertices())
    throw std::invalid_argument(surface.name() +
                                ": no contour vertex converges onto F = 0 (is the gradient zero "
                                "on the surface, e.g. F squared?)");
  if (options.smoothing_iterations > 0) {
    SmoothingOptions smoothing;
    smoothing.k = 0.0;
    smoothing.iterations = options.smoothing_iterations;
    smooth_tangentially(mesh, surface, smoothing);
  }
  if (info) *info = {contour.triangles.size(), unpaired, failures, spacing};
  return mesh;
}

}  // namespace dynamesh
