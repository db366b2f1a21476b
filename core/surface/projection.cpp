#include "core/surface/projection.h"

#include <cmath>

namespace dynamesh {

namespace {

// |F| / |grad F| is the distance to the surface to first order: a tolerance in length units
// that does not depend on how F is scaled (twist's F is dimensionless, sphere's a distance).
bool close_enough(double f, double gnorm, double tolerance_length) {
  return std::abs(f) <= tolerance_length * gnorm;
}

}  // namespace

ProjectionResult project_to_surface(const ImplicitSurface& surface, const Vec3& x,
                                    const ProjectionOptions& options) {
  ProjectionStart start;
  start.point = x;
  start.value = surface.value_gradient(x, start.gradient);
  return project_to_surface(surface, start, options);
}

ProjectionResult project_to_surface(const ImplicitSurface& surface, const ProjectionStart& start,
                                    const ProjectionOptions& options) {
  const double scale = surface.length_scale();
  const double tolerance_length = options.tolerance * scale;
  ProjectionResult result;
  result.point = start.point;
  Vec3 g = start.gradient;
  double f = start.value;
  result.residual = std::abs(f);
  result.value = f;
  result.gradient = g;
  if (!std::isfinite(f)) return result;
  for (;;) {
    const double g2 = g.squaredNorm();
    const double gnorm = std::sqrt(g2);
    if (!std::isfinite(g2) || !(gnorm > 0.0)) return result;  // nowhere to go
    if (close_enough(f, gnorm, tolerance_length)) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= options.max_iterations) return result;
    Vec3 step = (f / g2) * g;
    // A nearly flat F proposes huge steps; no projection should cross the whole scene.
    const double length = std::abs(f) / gnorm;
    const double longest = options.max_step > 0.0 ? options.max_step : scale;
    if (length > longest) step *= longest / length;
    Vec3 next = result.point - step;
    Vec3 g_next;
    double f_next = surface.value_gradient(next, g_next);
    int halvings = 0;
    while (!(std::abs(f_next) < std::abs(f)) && halvings < options.max_halvings) {
      step *= 0.5;
      next = result.point - step;
      f_next = surface.value_gradient(next, g_next);
      ++halvings;
    }
    if (!(std::abs(f_next) < std::abs(f))) return result;  // no descent along the gradient
    ++result.iterations;
    result.point = next;
    f = f_next;
    g = g_next;
    result.residual = std::abs(f);
    result.value = f;
    result.gradient = g;
  }
}

}  // namespace dynamesh
