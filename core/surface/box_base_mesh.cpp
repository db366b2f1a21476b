#include "core/surface/box_base_mesh.h"

#include <stdexcept>

#include "core/mesh/base_meshes.h"
#include "core/surface/projection.h"

namespace dynamesh {

Mesh48 make_projected_box_mesh(const ImplicitSurface& surface, const Box3& box,
                               const std::array<int, 3>& counts,
                               const std::function<Vec3(const Vec3&)>& place) {
  Mesh48 mesh = make_box_mesh(box, counts);
  for (const Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(surface, place(mesh.position(v)));
    if (!r.converged) {
      throw std::logic_error(surface.name() +
                             ": base mesh vertex did not project onto the surface");
    }
    mesh.position(v) = r.point;
  }
  return mesh;
}

}  // namespace dynamesh
