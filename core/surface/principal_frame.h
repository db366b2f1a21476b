// Principal curvatures and directions from a shape operator written in an orthonormal
// tangent frame: the last step shared by the parametric (fundamental forms) and implicit
// (gradient and Hessian, Goldman 2005) curvature formulas.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/surface.h"

namespace dynamesh {

// `shape` is the symmetric shape operator in the frame (e1, e2), with e1 x e2 = normal, already
// in surface.h's sign convention (a sphere with outward normal has shape = I / R). Returns
// k1 >= k2 with unit directions dir1, dir2 (dir1 x dir2 = normal).
PrincipalCurvatures principal_curvatures_in_frame(const Mat2& shape, const Vec3& e1, const Vec3& e2,
                                                  const Vec3& normal);

}  // namespace dynamesh
