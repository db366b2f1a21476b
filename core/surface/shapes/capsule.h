// The rest shape of the capsule-bend scene (SCENES.md): the points at distance r from the
// segment from (-h, 0, 0) to (h, 0, 0). F0(q) = |q - c(q)| - r, c(q) = (clamp(q.x, -h, h), 0, 0),
// a true signed distance: smooth (C^1, with a Hessian that jumps where the cylinder meets a cap)
// everywhere but on the segment itself.
#pragma once

#include <algorithm>

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"

namespace dynamesh {

struct Capsule {
  double half_length = 1.5;  // h
  double radius = 0.4;       // r

  double value(const Vec3& q) const;
  // Inline (with BendMap::to_rest): the capsule-bend scene evaluates F and grad F some 3 million
  // times a step at 10^6 triangles, and two calls into other files stood between them.
  double value_gradient(const Vec3& q, Vec3& gradient) const {
    const Vec3 d = offset(q);
    const double dist = d.norm();
    // On the segment the distance has no gradient; zero tells projection to stop there.
    gradient = dist > 0.0 ? Vec3(d / dist) : Vec3::Zero();
    return dist - radius;
  }
  ScalarJet jet(const Vec3& q) const;
  // Nearest point of the surface (on the segment itself: a point of the circle around it).
  Vec3 closest_point(const Vec3& q) const;

  // q - c(q): the offset from the nearest point of the segment.
  Vec3 offset(const Vec3& q) const {
    return {q.x() - std::clamp(q.x(), -half_length, half_length), q.y(), q.z()};
  }
};

}  // namespace dynamesh
