#include "core/adapt/surface_probe.h"

#include <cmath>

#include "core/surface/projection.h"
#include "core/surface/surface_distance.h"

namespace dynamesh {

SurfaceProbe::SurfaceProbe(const Surface& surface)
    : surface_(surface),
      parametric_(dynamic_cast<const ParametricSurface*>(&surface)),
      implicit_(dynamic_cast<const ImplicitSurface*>(&surface)),
      // Beyond this the first-order distance may be off by more than a few per cent.
      first_order_limit_(0.02 * surface.length_scale()) {}

void SurfaceProbe::place_split_vertex(Mesh48& mesh, const DiamondChange& change) const {
  if (parametric_) {
    // The mesh put (u, v) at the plain average, wrong across a periodic seam.
    const Vec2& a = mesh.uv(change.parents[0]);
    const Vec2 b = parametric_->unwrap_near(mesh.uv(change.parents[1]), a);
    mesh.uv(change.vertex) = parametric_->wrap_into_domain(0.5 * (a + b));
  }
}

bool SurfaceProbe::project_vertex(Mesh48& mesh, Vertex v) const {
  if (parametric_) {
    mesh.position(v) = parametric_->position(mesh.uv(v));
    return true;
  }
  const ProjectionResult r = project_to_surface(*implicit_, mesh.position(v));
  mesh.position(v) = r.point;
  return r.converged;
}

Vec3 SurfaceProbe::predicted_motion(const Mesh48& mesh, Vertex v, const Vec3* rest) const {
  const Vec3& p = mesh.position(v);
  if (parametric_) return parametric_->position(mesh.uv(v)) - p;
  const Vec3 x = rest && follows_material() ? implicit_->from_rest(*rest) : p;
  Vec3 g;
  const double f = implicit_->value_gradient(x, g);
  const double g2 = g.squaredNorm();
  const Vec3 newton = g2 > 0 ? Vec3(-f / g2 * g) : Vec3::Zero();
  return x + newton - p;
}

Vec3 SurfaceProbe::residual_at(const Vec3 p[3], const Vec2 uv[3], const Vec3& b) const {
  const Vec3 x = b[0] * p[0] + b[1] * p[1] + b[2] * p[2];
  if (parametric_) {
    // Interpolate (u, v) continuously across a periodic seam.
    const Vec2 uv1 = parametric_->unwrap_near(uv[1], uv[0]);
    const Vec2 uv2 = parametric_->unwrap_near(uv[2], uv[0]);
    return x - parametric_->position(
                   parametric_->wrap_into_domain(b[0] * uv[0] + b[1] * uv1 + b[2] * uv2));
  }
  return Vec3(signed_distance(x), 0, 0);
}

double SurfaceProbe::signed_distance(const Vec3& x) const {
  Vec3 g;
  const double f = implicit_->value_gradient(x, g);
  const double gnorm = g.norm();
  const double first_order = f / gnorm;
  if (gnorm > 0 && std::abs(first_order) < first_order_limit_) return first_order;
  return std::copysign(distance_to_surface(*implicit_, x), f);
}

Vec3 SurfaceProbe::normal_at(const Mesh48& mesh, Vertex v) const {
  if (parametric_) return parametric_->normal(mesh.uv(v));
  Vec3 g;
  implicit_->value_gradient(mesh.position(v), g);
  const double n = g.norm();
  return n > 0 ? Vec3(g / n) : Vec3::UnitZ();
}

}  // namespace dynamesh
