// Guards for typed formulas (issue 8): a formula is evaluated on a grid over its bounds or
// domain when the surface is built and again at every set_time(), before the adapter touches
// the mesh, so that a formula that is (or becomes) NaN or infinite, a surface that has no zero
// crossing inside its bounds or leaves them, or a periodic surface whose seam does not close,
// is reported as one clear std::invalid_argument instead of a crash or an endless refinement.
// A grid cannot see everything (a NaN in a pocket between grid points); it catches the
// mistakes people make, which are not pockets.
#pragma once

#include <string>

#include "core/geometry/vector_types.h"
#include "core/io/number_text.h"
#include "core/surface/expression/expression.h"
#include "core/surface/surface.h"

namespace dynamesh {

// What a scan of F(x, y, z, t) over a box found.
struct ImplicitScan {
  Vec3 interior{Vec3::Zero()};  // a point with F < 0 (the centroid of the grid's negative
                                // points when F < 0 there, else the most negative point)
  double min_value = 0.0;
};

// Scans F on an n^3 grid over `box` at time t (plus `extra_point`, e.g. the last interior
// point, so a thin shape between grid points is not lost); throws when F is not finite at a
// grid point, is nowhere negative (no zero crossing) or is negative on the box's sides (the
// surface is not inside the box).
ImplicitScan scan_implicit(const Expression& f, const std::string& formula_text, const Box3& box,
                           double t, int n, const Vec3* extra_point = nullptr);

// Scans S(u, v, t) = `position` on an n^2 grid over `domain` at time t; throws when S is not
// finite at a grid point or does not close up along a periodic direction. Returns the
// bounding box of the grid's points.
Box3 scan_parametric(const std::function<Vec3(const Vec2&)>& position,
                     const std::string& role_and_formula, const ParameterDomain& domain, double t,
                     int n);

}  // namespace dynamesh
