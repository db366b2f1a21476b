#include "core/surface/surface_distance.h"

#include <cmath>
#include <limits>

namespace dynamesh {

double distance_to_surface(const ImplicitSurface& surface, const Vec3& x,
                           const ProjectionOptions& options) {
  const ProjectionResult r = project_to_surface(surface, x, options);
  const double walked = (x - r.point).norm();
  if (r.converged) return walked;
  Vec3 g;
  const double f = surface.value_gradient(r.point, g);
  const double gnorm = g.norm();
  if (!std::isfinite(f) || !(gnorm > 0.0) || !std::isfinite(gnorm)) {
    return std::numeric_limits<double>::infinity();
  }
  return walked + std::abs(f) / gnorm;
}

double distance_to_surface(const ParametricSurface& surface, const Vec3& x, const Vec2& uv) {
  return (x - surface.position(uv)).norm();
}

}  // namespace dynamesh
