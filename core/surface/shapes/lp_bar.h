// The rest shape of the twist scene (SCENES.md; de Goes et al. 2006, Section 4.4): the
// extrusion along x of the Lp curve |y|^p + |z|^p = r^p, closed by superelliptic ends,
//   F0(q) = ( (|(q.y, q.z)|_p / r)^s + |q.x / h|^s )^(1/s) - 1,
// i.e. the Ls norm of (|(q.y, q.z)|_p / r, q.x / h), minus one. Smooth and convex for
// p, s >= 2; F0 is dimensionless (about distance / r near the sides).
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"

namespace dynamesh {

struct LpBar {
  double half_length = 1.5;  // h
  double radius = 0.4;       // r
  double p = 4.0;            // exponent of the cross-section
  double s = 8.0;            // exponent joining the sides to the ends

  double value(const Vec3& q) const;
  double value_gradient(const Vec3& q, Vec3& gradient) const;
  ScalarJet jet(const Vec3& q) const;
  // The rest shape's bounding box: [-h, h] x [-r, r]^2.
  Box3 bounds() const;
};

}  // namespace dynamesh
