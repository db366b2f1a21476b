// SurfaceProbe: the adapter's one door to the surface, hiding whether it is parametric or
// implicit. It brings vertices onto S(t) (normal correction) and measures the distance of
// mesh points to S(t) (SCENES.md, "Error of a mesh"). Thread-safe: const evaluation only.
#pragma once

#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/projection.h"
#include "core/surface/surface.h"

namespace dynamesh {

class SurfaceProbe {
 public:
  explicit SurfaceProbe(const Surface& surface);

  bool parametric() const { return parametric_ != nullptr; }
  const Surface& surface() const { return surface_; }

  // Moves v onto the surface (parametric: evaluates at its (u, v); implicit: Newton from its
  // position). Returns false when an implicit projection did not converge (v is left at the
  // last iterate, which is still closer than where it started).
  bool project_vertex(Mesh48& mesh, Vertex v) const;
  // Whether vertices are carried through the surface's rest space between steps
  // (ImplicitSurface::has_rest_map); then rest_point() before the surface's time changes and
  // carry_vertex() after it move a vertex with the material, before project_vertex().
  bool follows_material() const { return implicit_ != nullptr && implicit_->has_rest_map(); }
  Vec3 rest_point(const Mesh48& mesh, Vertex v) const {
    return implicit_->to_rest(mesh.position(v));
  }
  void carry_vertex(Mesh48& mesh, Vertex v, const Vec3& rest) const {
    mesh.position(v) = implicit_->from_rest(rest);
  }
  // How far v must move to reach the surface at its current time, to first order (the
  // motion sub-stepping plans with, motion_substeps.h), in two halves so that a caller can
  // carry many vertices before it evaluates at any of them (predict_displacements).
  // prediction_from(): where the prediction starts: parametric S(u, v) itself; along the rest
  // map from `rest` (recorded before the time changed; null: none); otherwise p.
  // predicted_motion_from(): the motion from there: parametric S(u, v) - p; otherwise one
  // Newton step from it, -F grad F / |grad F|^2 (without a rest map: the normal velocity
  // v = -F_t grad F / |grad F|^2 integrated over the step, F(p) being 0 before it), added to
  // the carry. `start` (implicit only; may be null) receives the point the prediction started
  // from and F, grad F there: the adapter's normal correction continues Newton from it when
  // the surface's time has not changed since (one evaluation per vertex less in a step without
  // sub-steps).
  Vec3 prediction_from(const Mesh48& mesh, Vertex v, const Vec3* rest) const {
    if (parametric_) return parametric_->position(mesh.uv(v));
    return rest && follows_material() ? implicit_->from_rest(*rest) : mesh.position(v);
  }
  Vec3 predicted_motion_from(const Mesh48& mesh, Vertex v, const Vec3& from,
                             ProjectionStart* start = nullptr) const;
  // Sets a split-born vertex's parameters to its parent edge's midpoint (continuous across a
  // periodic seam); call before project_vertex.
  void place_split_vertex(Mesh48& mesh, const DiamondChange& change) const;
  // project_vertex for a vertex a split just created. Implicit: when Newton from the edge's
  // midpoint slides mostly sideways (the edge bridges a crease or a sulcus and the nearest
  // point is on a wall), the vertex goes instead to the nearest zero of F along the
  // diamond's normal where the new faces face up grad F, down into the crease (not to F's far
  // sheet, which that line can meet first). Without this a bridging edge never gets shorter
  // than the gap it spans and the split queue grows without end.
  // With the fold guard on (the rest of a step in which the mesh's topology was repaired, issue
  // 16), a place that turns one of the new faces against grad F is passed over for the next,
  // and when every place does the vertex stays at the edge's midpoint: across a neck thinner
  // than the edges (just after a merge) Newton or the nearest zero along the normal can land
  // on the neck's far wall, and the faces folded there are beyond the fold repair's reach.
  // The adapter holds the faces of such a vertex and projects it before publishing
  // (Adapter::place_guarded_vertices).
  bool project_split_vertex(Mesh48& mesh, const DiamondChange& change) const;
  // Where a split puts its new vertex: place_split_vertex, then project_split_vertex (false
  // when the projection failed). The adapter's rule, which its local repairs plan on too.
  bool put_split_vertex(Mesh48& mesh, const DiamondChange& change) const {
    place_split_vertex(mesh, change);
    return project_split_vertex(mesh, change);
  }
  void set_split_fold_guard(bool on) { split_fold_guard_ = on; }
  bool split_fold_guard() const { return split_fold_guard_; }

  // Distance to the surface of the point with barycentric coordinates b over the triangle
  // (v0, v1, v2) (positions p, parameters uv). Implicit: the first-order distance
  // |F| / |grad F|, accurate to second order for errors small against the curvature radius
  // (SCENES.md), with a full Newton projection when it is not small.
  double error_at(const Vec3 p[3], const Vec2 uv[3], const Vec3& b) const {
    return residual_at(p, uv, b).norm();
  }
  // The error as a vector that varies smoothly over the triangle (for QuadraticErrorModel):
  // parametric x - S(uv); implicit (signed distance, 0, 0).
  Vec3 residual_at(const Vec3 p[3], const Vec2 uv[3], const Vec3& b) const;
  // Implicit only: the signed distance of x to the surface (negative inside), the scalar
  // residual_at() wraps.
  double signed_distance(const Vec3& x) const;
  // Critical points of F near its zero set (issue 16: a neck about to pinch, tips about to
  // touch). Within r of one, grad F vanishes linearly (|grad F| ~ |Hess F| r) and the
  // first-order distance is off by about d / (2 r) relative: 15% (0.0099 against Newton's
  // 0.0116) on a blob's tip 0.033 from the saddle it was about to merge through. So within
  // kFirstOrderReach times the first-order distance of one (a 1% error) the full Newton
  // distance is taken.
  void set_singular_points(const std::vector<Vec3>& points) { singular_ = points; }
  static constexpr double kFirstOrderReach = 50.0;
  // signed_distance of a point x of the triangle p, at most its distance to a corner plus that
  // corner's own distance to the surface (nil for a corner on it).
  double signed_distance_in_triangle(const Vec3 p[3], const Vec3& x) const;

  // The length within which a vertex's Newton step is trusted to F's linear model: its shortest
  // incident edge (ProjectionOptions::quadratic_beyond; beyond it a long step, next to a
  // critical point, could carry the vertex past its neighbours and turn faces over).
  static double trusted_step(const Mesh48& mesh, Vertex v);

  // Unit normal of the surface at a vertex (parametric: at its (u, v)).
  Vec3 normal_at(const Mesh48& mesh, Vertex v) const;

 private:
  const Surface& surface_;
  const ParametricSurface* parametric_ = nullptr;
  const ImplicitSurface* implicit_ = nullptr;
  double first_order_limit_ = 0.0;
  bool split_fold_guard_ = false;
  std::vector<Vec3> singular_;
};

}  // namespace dynamesh
