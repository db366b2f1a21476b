// The geometric error of a mesh point: its distance to the true surface (SCENES.md, "Error of
// a mesh against its scene"; the sampled error of de Goes et al. 2006, Section 3.4).
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/projection.h"
#include "core/surface/surface.h"

namespace dynamesh {

// Implicit: |x - x*| with x* reached from x by Newton projection (projection.h). When the
// projection does not converge, |x - x_last| + |F(x_last)| / |grad F(x_last)| (the distance
// walked plus a first-order estimate of what remains), or +infinity where the gradient
// vanishes: an unmeasurable point counts as badly approximated, never as exact.
double distance_to_surface(const ImplicitSurface& surface, const Vec3& x,
                           const ProjectionOptions& options = {});

// Parametric: |x - S(u, v)| with (u, v) the point's parameter value.
double distance_to_surface(const ParametricSurface& surface, const Vec3& x, const Vec2& uv);

}  // namespace dynamesh
