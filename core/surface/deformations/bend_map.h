// The bend of the capsule-bend scene (SCENES.md; de Goes et al. 2006, Section 4.1): the rest
// x axis is wrapped onto a circle of curvature kappa about an axis parallel to z through
// (0, 1/kappa, 0), arc length preserved along the axis. to_rest() is SCENES.md's map p -> q
// and to_world() its inverse.
//
// SCENES.md writes the bend with rho0 = 1/kappa: theta = atan2(p.x, rho0 - p.y),
// rho = hypot(p.x, rho0 - p.y), q = (rho0 theta, rho0 - rho, p.z). For a gentle bend rho0 is
// huge and rho0 - rho cancels catastrophically (1e-7 error at kappa = 1e-9), so everything is
// evaluated in the scaled variables a = kappa p.x, b = 1 - kappa p.y, s = hypot(a, b) = kappa rho:
//   q.x = atan2(a, b) / kappa,   q.y = (1 - s) / kappa = (2 p.y - kappa (p.x^2 + p.y^2)) / (1 + s),
// which is the same function, exact to rounding for any kappa.
//
// to_rest() is inline, as Capsule::value_gradient is: the scene's F and grad F compose the two
// (mapped_value_gradient) about 3 million times a step at 10^6 triangles (issue 17).
#pragma once

#include <cmath>

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"
#include "core/surface/polynomial_atan.h"

namespace dynamesh {

namespace bend_map_detail {

struct Scaled {
  double a, b, s, theta;
};

inline Scaled scaled(double kappa, const Vec3& p) {
  Scaled v;
  v.a = kappa * p.x();
  v.b = 1.0 - kappa * p.y();
  v.s = std::sqrt(v.a * v.a + v.b * v.b);  // b is near 1: no overflow, no need for hypot
  v.theta = polynomial_atan2(v.a, v.b);    // glibc's atan2 was 10% of a capsule step
  return v;
}

inline Vec3 rest_point(double kappa, const Vec3& p, const Scaled& v) {
  const double qy = (2.0 * p.y() - kappa * (p.x() * p.x() + p.y() * p.y())) / (1.0 + v.s);
  return {v.theta / kappa, qy, p.z()};
}

// d q / d p from da = kappa dp.x, db = -kappa dp.y, d theta = (b da - a db) / s^2 and
// ds = (a da + b db) / s:  dqx/dpx = b/s^2, dqx/dpy = a/s^2, dqy/dpx = -a/s, dqy/dpy = b/s.
inline Mat3 rest_jacobian(const Scaled& v) {
  const double s2 = v.s * v.s;
  Mat3 J;
  J << v.b / s2, v.a / s2, 0.0,    //
      -v.a / v.s, v.b / v.s, 0.0,  //
      0.0, 0.0, 1.0;
  return J;
}

}  // namespace bend_map_detail

class BendMap {
 public:
  // Below this curvature the map is the identity (SCENES.md).
  static constexpr double kMinCurvature = 1e-9;

  explicit BendMap(double kappa = 0.0) : kappa_(kappa) {}
  double curvature() const { return kappa_; }
  bool is_identity() const { return !(std::abs(kappa_) > kMinCurvature); }

  Vec3 to_rest(const Vec3& p) const {
    if (is_identity()) return p;
    using namespace bend_map_detail;
    return rest_point(kappa_, p, scaled(kappa_, p));
  }
  Vec3 to_rest(const Vec3& p, Mat3& jacobian) const {
    if (is_identity()) {
      jacobian.setIdentity();
      return p;
    }
    using namespace bend_map_detail;
    const Scaled v = scaled(kappa_, p);
    jacobian = rest_jacobian(v);
    return rest_point(kappa_, p, v);
  }
  MapJet to_rest_jet(const Vec3& p) const;
  // Inverse of to_rest for rest points with q.y < 1/kappa and |kappa q.x| < pi.
  Vec3 to_world(const Vec3& q) const;

 private:
  double kappa_;
};

}  // namespace dynamesh
