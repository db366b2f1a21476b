// Moving a mesh vertex along the surface: a displacement in space, taken back onto S.
// Parametric surfaces move in (u, v) through the pseudo-inverse of the Jacobian [Su Sv]
// (parameter-domain boundary vertices keep their boundary coordinate, so corners stay put and
// sides slide along themselves); implicit ones move in space and are Newton-projected.
// Shared by the tangential smoothing and the fold repair.
#pragma once

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

// Parametric: the (u, v) step whose image best matches `move`; false when the vertex is a
// domain corner or the step is not finite.
bool parametric_move(const ParametricSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                     Vec2& uv, Vec3& position);

// Implicit: p + move projected; false (and ++failures) when the projection did not converge.
// `value`, `gradient` (optional): F and grad F where the vertex lands.
bool implicit_move(const ImplicitSurface& s, const Mesh48& mesh, Vertex v, const Vec3& move,
                   Vec3& position, std::size_t& failures, double* value = nullptr,
                   Vec3* gradient = nullptr);

// Unit normal of S at a vertex (parametric: at its (u, v); implicit: grad F / |grad F|).
Vec3 surface_normal_at(const Surface& s, const Mesh48& mesh, Vertex v);

}  // namespace dynamesh
