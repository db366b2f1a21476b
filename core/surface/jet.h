// Second-order jets (value, first and second derivatives) of a scalar field and of a map of
// space, and their composition by the chain rule. The deformed implicit scenes are
// F(p) = F0(q(p)) with a rest shape F0 and a map q from world to rest space (SCENES.md), so
//   grad F = J^T grad F0,   Hess F = J^T (Hess F0) J + sum_k dF0/dq_k Hess q_k.
#pragma once

#include <array>

#include "core/geometry/vector_types.h"

namespace dynamesh {

struct ScalarJet {
  double value = 0.0;
  Vec3 gradient{Vec3::Zero()};
  Mat3 hessian{Mat3::Zero()};
};

struct MapJet {
  Vec3 value{Vec3::Zero()};
  Mat3 jacobian{Mat3::Identity()};  // jacobian(i, j) = d q_i / d p_j
  std::array<Mat3, 3> hessians{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};  // Hess q_i
};

inline ScalarJet compose(const ScalarJet& outer, const MapJet& inner) {
  ScalarJet r;
  r.value = outer.value;
  r.gradient = inner.jacobian.transpose() * outer.gradient;
  r.hessian = inner.jacobian.transpose() * outer.hessian * inner.jacobian;
  for (int k = 0; k < 3; ++k) r.hessian += outer.gradient(k) * inner.hessians[k];
  return r;
}

// F(p) = F0(q(p)) for a rest shape (value_gradient, jet) and a map to rest space (to_rest
// with its Jacobian, to_rest_jet): what every deformed implicit scene evaluates.
template <class Shape, class Map>
double mapped_value_gradient(const Shape& shape, const Map& map, const Vec3& p, Vec3& gradient) {
  Mat3 jacobian;
  const Vec3 q = map.to_rest(p, jacobian);
  Vec3 rest_gradient;
  const double f = shape.value_gradient(q, rest_gradient);
  gradient = jacobian.transpose() * rest_gradient;
  return f;
}

template <class Shape, class Map>
Mat3 mapped_hessian(const Shape& shape, const Map& map, const Vec3& p) {
  const MapJet inner = map.to_rest_jet(p);
  return compose(shape.jet(inner.value), inner).hessian;
}

// All three from one evaluation of the map and the shape (ImplicitSurface::
// value_gradient_hessian); the gradient is the one mapped_value_gradient() returns.
template <class Shape, class Map>
double mapped_jet(const Shape& shape, const Map& map, const Vec3& p, Vec3& gradient,
                  Mat3& hessian) {
  const MapJet inner = map.to_rest_jet(p);
  const ScalarJet j = compose(shape.jet(inner.value), inner);
  gradient = j.gradient;
  hessian = j.hessian;
  return j.value;
}

}  // namespace dynamesh
