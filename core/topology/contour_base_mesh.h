// A base mesh of any genus and any number of components from F itself (issue 16): F's zero set
// contoured by marching tetrahedra on a coarse grid over the surface's bounds, its triangles
// paired by a perfect matching (triangle_pairing.h) into a triangulated quadrangulation, every
// vertex Newton-projected onto F = 0 and the result relaxed by plain tangential smoothing
// (Equation 1 with k = 0), whose guards keep every triangle facing outwards. The adapter's
// split queue then refines it as it refines any base mesh. Should a matching leave triangles
// unpaired (it cannot on a closed manifold), Velho's construction (make_48_mesh) is used instead.
#pragma once

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct ContourBaseOptions {
  // Grid spacing in scene units; 0 means the bounds' longest side / cells_along_longest.
  double spacing = 0.0;
  int cells_along_longest = 24;
  int smoothing_iterations = 4;
  // The level set contoured, F = level, before every vertex is Newton-projected onto F = 0. A
  // mid-run re-base next to an event sets it (TopologyMonitor::clear_level) so that a critical
  // point closer to zero than the grid resolves lies on its own side of the contour: two tips
  // closer than a cell are contoured apart, a new neck thinner than a cell is contoured open.
  double level = 0.0;
};

struct ContourBaseInfo {
  std::size_t contour_triangles = 0;  // from marching tetrahedra
  std::size_t unpaired = 0;           // left by the matching (then Velho's construction)
  std::size_t unprojected = 0;        // vertices left at their contour position
  double spacing = 0.0;
};

// Throws std::invalid_argument when F has no zero crossing on the grid, is negative on the
// bounds' sides, or no contour vertex projects onto F = 0.
Mesh48 make_contour_base_mesh(const ImplicitSurface& surface,
                              const ContourBaseOptions& options = {},
                              ContourBaseInfo* info = nullptr);

}  // namespace dynamesh
