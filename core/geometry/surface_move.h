// Moving a mesh vertex along the surface: a displacement in space, taken back onto S.
// Parametric surfaces move in (u, v) through the pseudo-inverse of the Jacobian [Su Sv]
// (parameter-domain boundary vertices keep their boundary coordinate, so corners stay put and
// sides slide along themselves); implicit ones move in space and are Newton-projected.
// Shared by the tangential smoothing and the fold repair.
#pragma once

#include "core/mesh/mesh48.h"
#include "core/surface/projection.h"
#include "core/surface/surface.h"

namespace dynamesh {

// Parametric: the (u, v) step whose image best matches `move`; false when the vertex is a
// domain corner or the step is not finite.
bool parametric_move(const ParametricSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                     Vec2& uv, Vec3& position);

// Implicit: p + move projected; false (and ++failures) when the projection did not converge.
// `value`, `gradient` (optional): F and grad F where the vertex lands. `start` (optional): where
// the projection starts instead of p + move (second_order_landing), the same surface point to
// the projection's tolerance.
bool implicit_move(const ImplicitSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                   Vec3& position, std::size_t& failures, double* value = nullptr,
                   Vec3* gradient = nullptr, const Vec3* start = nullptr);

// Where p + move lands on an implicit S to second order, from F and grad F at p (`at_p`, its
// point p) and S's principal curvatures near p (ImplicitSurface::curvatures: k_i =
// u_i^T Hess F u_i / |grad F|). With n = grad F / |grad F| and the vertex placed at
// p + move + h n,
//   F ~ F(p) + grad F . move + |grad F| h + |grad F| (k1 (move . u1)^2 + k2 (move . u2)^2) / 2,
// which vanishes for the h returned here (the Hessian's normal-tangential terms enter at third
// order). A projection started there needs one evaluation where a tangential move starting at
// p + move needed a Newton step and two. Falls back to p + move where grad F vanishes, or where
// the move is long against the curvature radius or far from tangential (|k| |move| or the
// first-order normal part over |move| above 0.1): there the model does not hold, and on a
// distance field between nearly touching sheets a long correction could start the projection
// nearer the other sheet.
Vec3 second_order_landing(const PointEvaluation& at_p, const PrincipalCurvatures& k,
                          const Vec3& move);

// Unit normal of S at a vertex (parametric: at its (u, v); implicit: grad F / |grad F|).
Vec3 surface_normal_at(const Surface& s, const Mesh48& mesh, Vertex v);

}  // namespace dynamesh
