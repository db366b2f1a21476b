#include "core/surface/projection.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace dynamesh {

namespace {

// |F| / |grad F| is the distance to the surface to first order: a tolerance in length units
// that does not depend on how F is scaled (twist's F is dimensionless, sphere's a distance).
bool close_enough(double f, double gnorm, double tolerance_length) {
  return std::abs(f) <= tolerance_length * gnorm;
}

}  // namespace

Vec3 newton_step_bounded(const ImplicitSurface& surface, const Vec3& x, double f, const Vec3& g,
                         const ProjectionOptions& options) {
  const double g2 = g.squaredNorm();
  const Vec3 newton = (-f / g2) * g;
  const double length = std::abs(f) / std::sqrt(g2);
  if (!(options.quadratic_beyond > 0.0) || length <= options.quadratic_beyond) return newton;
  // Along u = -sign(f) grad F / |grad F|: sign(f) F(x + s u) ~ |f| - |g| s + k s^2 / 2, with
  // k = sign(f) u^T H u; its smallest positive root, in the form that stays exact as |g| -> 0.
  const Mat3 hessian = surface.hessian(x);
  const double gnorm = std::sqrt(g2);
  const Vec3 u = newton / length;
  const double k = std::copysign(1.0, f) * u.dot(hessian * u);
  const double discriminant = g2 - 2.0 * k * std::abs(f);
  if (discriminant >= 0.0) {
    const double s = 2.0 * std::abs(f) / (gnorm + std::sqrt(discriminant));
    return std::min(s, length) * u;
  }
  // No root along the gradient (F's model curves back before reaching zero): the nearest root
  // along an eigenvector of the Hessian whose eigenvalue has the sign opposite to f.
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(hessian);
  double best = length;
  Vec3 step = (options.quadratic_beyond / length) * newton;
  for (int i = 0; i < 3; ++i) {
    const double lambda = eigen.eigenvalues()[i];
    if (!(lambda * f < 0.0)) continue;
    const double s = std::sqrt(2.0 * std::abs(f) / std::abs(lambda));
    if (s >= best) continue;
    const Vec3 e = eigen.eigenvectors().col(i);
    best = s;
    step = (e.dot(u) >= 0.0 ? s : -s) * e;
  }
  return step;
}

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
    Vec3 step = -newton_step_bounded(surface, result.point, f, g, options);
    // A nearly flat F proposes huge steps; no projection should cross the whole scene.
    const double length = options.quadratic_beyond > 0.0 ? step.norm() : std::abs(f) / gnorm;
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
