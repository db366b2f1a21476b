// Barycentric coordinates across a bisection (see Bisection in mesh48.h): where a point of
// the parent triangle (apex, a, b) lies in its children (m, apex, a) / (m, b, apex), m the
// midpoint of (a, b), and back. Coordinates are in each face's storage order. Used to carry
// samples and other surface-attached points through splits and welds.
#pragma once

namespace dynamesh {

// Which child holds the parent point (c_apex, c_a, c_b): 0 when c_a >= c_b, else 1.
template <class V>
int bisection_child(const V& parent) {
  return parent[1] >= parent[2] ? 0 : 1;
}

template <class V>
V to_child_coordinates(const V& p, int child) {
  using S = typename V::Scalar;
  if (child == 0) return V(S(2) * p[2], p[0], p[1] - p[2]);
  return V(S(2) * p[1], p[2] - p[1], p[0]);
}

template <class V>
V to_parent_coordinates(const V& c, int child) {
  using S = typename V::Scalar;
  const S half_m = S(0.5) * c[0];
  if (child == 0) return V(c[1], c[2] + half_m, half_m);
  return V(c[2], half_m, c[1] + half_m);
}

}  // namespace dynamesh
