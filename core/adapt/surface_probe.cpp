#include "core/adapt/surface_probe.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/fold_repair.h"
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
  ProjectionOptions o;
  o.quadratic_beyond = trusted_step(mesh, v);
  const ProjectionResult r = project_to_surface(*implicit_, mesh.position(v), o);
  mesh.position(v) = r.point;
  return r.converged;
}

double SurfaceProbe::trusted_step(const Mesh48& mesh, Vertex v) {
  double shortest = HUGE_VAL;
  const Vec3& p = mesh.position(v);
  mesh.for_each_corner_around(v, [&](const Corner& c) {
    const Vertex next = mesh.vertices(c.face)[static_cast<std::size_t>((c.local + 1) % 3)];
    shortest = std::min(shortest, (mesh.position(next) - p).squaredNorm());
  });
  return std::isfinite(shortest) ? std::sqrt(shortest) : 0.0;
}

bool SurfaceProbe::project_split_vertex(Mesh48& mesh, const DiamondChange& change) const {
  if (parametric_) return project_vertex(mesh, change.vertex);
  const Vec3 m = mesh.position(change.vertex);
  const Vec3 a = mesh.position(change.parents[0]), b = mesh.position(change.parents[1]);
  const double length = (b - a).norm();
  // A midpoint lies within about half an edge of the surface; a longer jump is Newton lost
  // where |grad F| is small, and lands on another part of the surface.
  ProjectionOptions local;
  local.max_step = 0.5 * length;
  const ProjectionResult newton = project_to_surface(*implicit_, m, local);
  Vec3 normal = Vec3::Zero();
  for (int h = 0; h < change.count; ++h) {
    const Vec3 apex = mesh.position(change.halves[h].parent_vertices[0]);
    const Vec3 pa = mesh.position(change.halves[h].parent_vertices[1]);
    const Vec3 pb = mesh.position(change.halves[h].parent_vertices[2]);
    normal += (pa - apex).cross(pb - apex);
  }
  // Whether the vertex at p leaves the split's new faces facing up grad F at their corners
  // (the fold screen's own test).
  const auto keeps_faces_up = [&](const Vec3& p) {
    mesh.position(change.vertex) = p;
    for (int h = 0; h < change.count; ++h)
      for (const Face f : change.halves[h].children)
        if (folded_against_surface(mesh, *implicit_, f)) return false;
    return true;
  };
  const Vec3 d = newton.point - m;
  const double along = std::abs(d.dot(normal.normalized()));
  const bool sideways = normal.norm() > 0 && d.norm() > 0.1 * length && along < 0.7 * d.norm();
  if (newton.converged && !sideways && d.norm() <= length &&
      (!split_fold_guard_ || keeps_faces_up(newton.point))) {
    mesh.position(change.vertex) = newton.point;
    return true;
  }
  // Nearest sign change of F along the normal line through m, within 4 edge lengths, where the
  // new faces face up: the line, as long as it is, also meets F's other sheets, across a gyrus
  // or the cavity, and a vertex put there turns all its faces over, far beyond the fold
  // repair's reach. Colin27 swept in 4 steps (closing 2) with the projection's tolerance
  // perturbed to 0.9e-10: a 4 mm edge's midpoint, Newton 0.87 mm sideways, met F 14.8 mm down
  // the line; the vertex's 4 faces stayed folded and the last frame read 7.50 mm against 0.625.
  // The check costs 12 evaluations only on this rare path.
  const Vec3 n = normal.normalized();
  const double f0 = implicit_->value(m);
  const double step = length / 16.0;
  for (int i = 1; i <= 64 && normal.norm() > 0; ++i) {
    for (const double sign : {-1.0, 1.0}) {
      const double s0 = sign * (i - 1) * step, s1 = sign * i * step;
      if ((implicit_->value(m + s1 * n) < 0.0) == (f0 < 0.0)) continue;
      double lo = s0, hi = s1;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        ((implicit_->value(m + mid * n) < 0.0) == (f0 < 0.0) ? lo : hi) = mid;
      }
      const ProjectionResult r = project_to_surface(*implicit_, m + 0.5 * (lo + hi) * n, local);
      if (r.converged && (r.point - m).norm() <= 4.0 * length && keeps_faces_up(r.point)) {
        mesh.position(change.vertex) = r.point;
        return true;
      }
    }
  }
  // With the fold guard on and no place that keeps the new faces up: the vertex stays on its
  // edge, where the new faces are their parents' halves (facing as they did); the next
  // sub-step's correction moves it once the neck has widened.
  if (split_fold_guard_) {
    mesh.position(change.vertex) = m;
    return false;
  }
  mesh.position(change.vertex) = newton.point;
  return newton.converged;
}

Vec3 SurfaceProbe::predicted_motion_from(const Mesh48& mesh, Vertex v, const Vec3& x,
                                         ProjectionStart* start) const {
  const Vec3& p = mesh.position(v);
  if (parametric_) return x - p;
  Vec3 g;
  const double f = implicit_->value_gradient(x, g);
  if (start) *start = ProjectionStart{x, f, g};
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
  return Vec3(signed_distance_in_triangle(p, x), 0, 0);
}

// No point of the triangle is farther from the surface than from a corner plus that corner's
// own distance (nil for a corner projected onto F). The cap matters where |grad F| is small
// (between nearly touching sheets of a brain layer): there F / |grad F| and Newton's path both
// overstate the distance without bound, and a face whose error cannot fall by splitting is
// split without end. A corner's distance is read only when the cap binds: a split vertex the
// fold guard kept on its edge (project_split_vertex, on a neck just after a merge) is off the
// surface, and capping at the corner alone read 0.008 on faces 0.027 from three merging blobs.
double SurfaceProbe::signed_distance_in_triangle(const Vec3 p[3], const Vec3& x) const {
  const double sd = signed_distance(x);
  double cap2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) cap2 = std::min(cap2, (x - p[i]).squaredNorm());
  if (sd * sd <= cap2) return sd;
  double cap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    cap = std::min(cap, (x - p[i]).norm() + std::abs(signed_distance(p[i])));
  return std::abs(sd) > cap ? std::copysign(cap, sd) : sd;
}

double SurfaceProbe::signed_distance(const Vec3& x) const {
  Vec3 g;
  const double f = implicit_->value_gradient(x, g);
  const double gnorm = g.norm();
  const double first_order = f / gnorm;
  if (gnorm > 0 && std::abs(first_order) < first_order_limit_) {
    const double reach2 = kFirstOrderReach * kFirstOrderReach * first_order * first_order;
    bool near = false;
    for (const Vec3& c : singular_) near = near || (x - c).squaredNorm() < reach2;
    if (!near) return first_order;
  }
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
