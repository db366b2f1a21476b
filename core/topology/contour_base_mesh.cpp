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

// Each pair's shared edge becomes the refinement edge of both.
Mesh48 paired_mesh(std::vector<Vec3> positions,
                   const std::vector<std::array<std::uint32_t, 3>>& triangles,
                   const std::vector<std::int64_t>& partner) {
  return Mesh48::from_base_triangles(std::move(positions), {},
                                     refinement_edge_first(triangles, partner));
}

}  // namespace

Mesh48 make_contour_base_mesh(const ImplicitSurface& surface, const ContourBaseOptions& options,
                              ContourBaseInfo* info) {
  const Box3 box = surface.bounds();
  const double spacing = options.spacing > 0
                             ? options.spacing
                             : box.size().maxCoeff() / std::max(2, options.cells_along_longest);
  const ContourGrid grid = make_contour_grid(box, spacing);
  std::vector<double> values = sample_grid(surface, grid);
  for (double& value : values) value -= options.level;
  const ContourMesh contour = marching_tetrahedra(grid, values);
  if (contour.triangles.empty())
    throw std::invalid_argument(surface.name() + ": F has no zero crossing on a grid of spacing " +
                                std::to_string(spacing) + " over the bounds");
  std::vector<Vec3> positions = contour.positions;
  constexpr double kMargin = 0.05;
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = root_on_edge(surface, contour.edges[i], kMargin, options.level);
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
  // A contour of F = level may travel twice the first-order distance |level| / |grad F| more.
  std::size_t failures = 0;
  for (const Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(surface, mesh.position(v));
    double reach = 0.1 * spacing;
    if (options.level != 0.0) {
      Vec3 g;
      surface.value_gradient(mesh.position(v), g);
      reach += 2.0 * std::abs(options.level) / std::max(g.norm(), 1e-300);
    }
    if (r.converged && (r.point - mesh.position(v)).norm() <= reach)
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
