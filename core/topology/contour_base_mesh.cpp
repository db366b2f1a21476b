#include "core/topology/contour_base_mesh.h"

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
    throw std::invalid_argument(surface.name() +
                                ": F has no zero crossing on a grid of spacing " +
                                std::to_string(spacing) + " over the bounds");
  const std::vector<std::int64_t> partner = pair_triangles(contour.positions, contour.triangles);
  std::size_t unpaired = 0;
  for (const std::int64_t p : partner) unpaired += p < 0;
  Mesh48 mesh = unpaired == 0 ? paired_mesh(contour.positions, contour.triangles, partner)
                              : make_48_mesh(contour.positions, {}, contour.triangles);
  for (const Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(surface, mesh.position(v));
    if (!r.converged)
      throw std::invalid_argument(surface.name() + ": a contour vertex did not converge onto F = 0 "
                                  "(is the gradient zero on the surface?)");
    mesh.position(v) = r.point;
  }
  if (options.smoothing_iterations > 0) {
    SmoothingOptions smoothing;
    smoothing.k = 0.0;
    smoothing.iterations = options.smoothing_iterations;
    smooth_tangentially(mesh, surface, smoothing);
  }
  if (info) *info = {contour.triangles.size(), unpaired, spacing};
  return mesh;
}

}  // namespace dynamesh
