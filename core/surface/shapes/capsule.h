// The rest shape of the capsule-bend scene (SCENES.md): the points at distance r from the
// segment from (-h, 0, 0) to (h, 0, 0). F0(q) = |q - c(q)| - r, c(q) = (clamp(q.x, -h, h), 0, 0),
// a true signed distance: smooth (C^1, with a Hessian that jumps where the cylinder meets a cap)
// everywhere but on the segment itself.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"

namespace dynamesh {

struct Capsule {
  double half_length = 1.5;  // h
  double radius = 0.4;       // r

  double value(const Vec3& q) const;
  double value_gradient(const Vec3& q, Vec3& gradient) const;
  ScalarJet jet(const Vec3& q) const;
  // Nearest point of the surface (on the segment itself: a point of the circle around it).
  Vec3 closest_point(const Vec3& q) const;
};

}  // namespace dynamesh
