#include "core/geometry/surface_move.h"

#include <algorithm>
#include <cmath>

#include "core/surface/projection.h"

namespace dynamesh {

bool parametric_move(const ParametricSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                     Vec2& uv, Vec3& position) {
  const ParameterDomain dom = s.domain();
  const Vec2 size = dom.max - dom.min;
  const Vec2 old = mesh.uv(v);
  bool fixed[2];
  const bool periodic[2] = {dom.periodic_u, dom.periodic_v};
  for (int a = 0; a < 2; ++a)
    fixed[a] = !periodic[a] && (std::abs(old[a] - dom.min[a]) < 1e-12 * size[a] ||
                                std::abs(old[a] - dom.max[a]) < 1e-12 * size[a]);
  if (fixed[0] && fixed[1]) return false;
  const ParametricDerivatives dv = s.derivatives(old);
  Eigen::Matrix<double, 3, 2> J;
  J << dv.su, dv.sv;
  Vec2 step = (J.transpose() * J).ldlt().solve(J.transpose() * move);
  for (int a = 0; a < 2; ++a)
    if (fixed[a]) step[a] = 0;
  if (!step.allFinite()) return false;
  uv = s.wrap_into_domain(old + step);
  position = s.position(uv);
  return true;
}

bool implicit_move(const ImplicitSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                   Vec3& position, std::size_t& failures, double* value, Vec3* gradient,
                   const Vec3* start) {
  const ProjectionResult r = project_to_surface(s, start ? *start : mesh.position(v) + move);
  if (!r.converged) {
    ++failures;
    return false;
  }
  position = r.point;
  if (value) *value = r.value;
  if (gradient) *gradient = r.gradient;
  return true;
}

namespace {
// second_order_landing's model holds for |k| |move| and the move's normal part (relative)
// below this: the landing is then within 0.15 |move| of p + move.
constexpr double kModelReach = 0.1;
}  // namespace

Vec3 second_order_landing(const PointEvaluation& at_p, const PrincipalCurvatures& k,
                          const Vec3& move) {
  const Vec3 straight = at_p.point + move;
  const double gnorm = at_p.gradient.norm();
  if (!(gnorm > 0.0)) return straight;
  const double length = move.norm();
  const double first = -(at_p.value + at_p.gradient.dot(move)) / gnorm;
  // The model is trusted only for a move short against the curvature radius and nearly
  // tangential: elsewhere (a distance field's kinks, sheets about to touch) the plain start is
  // no worse, and a long correction could reach across to another sheet.
  const double kmax = std::max(std::abs(k.k1), std::abs(k.k2));
  if (!(kmax * length <= kModelReach && std::abs(first) <= kModelReach * length)) return straight;
  const double a = move.dot(k.dir1), b = move.dot(k.dir2);
  const double h = first - 0.5 * (k.k1 * a * a + k.k2 * b * b);
  return straight + (h / gnorm) * at_p.gradient;
}

Vec3 surface_normal_at(const Surface& s, const Mesh48& mesh, Vertex v) {
  if (const auto* par = dynamic_cast<const ParametricSurface*>(&s)) return par->normal(mesh.uv(v));
  Vec3 g;
  static_cast<const ImplicitSurface&>(s).value_gradient(mesh.position(v), g);
  const double n = g.norm();
  return n > 0 ? Vec3(g / n) : Vec3::UnitZ();
}

}  // namespace dynamesh
