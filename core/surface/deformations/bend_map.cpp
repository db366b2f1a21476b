// SCENES.md writes the bend with rho0 = 1/kappa: theta = atan2(p.x, rho0 - p.y),
// rho = hypot(p.x, rho0 - p.y), q = (rho0 theta, rho0 - rho, p.z). For a gentle bend rho0 is
// huge and rho0 - rho cancels catastrophically (1e-7 error at kappa = 1e-9), so everything is
// evaluated in the scaled variables a = kappa p.x, b = 1 - kappa p.y, s = hypot(a, b) = kappa rho:
//   q.x = atan2(a, b) / kappa,   q.y = (1 - s) / kappa = (2 p.y - kappa (p.x^2 + p.y^2)) / (1 + s),
// which is the same function, exact to rounding for any kappa.
#include "core/surface/deformations/bend_map.h"

#include <cmath>

#include "core/surface/polynomial_atan.h"

namespace dynamesh {

namespace {

struct Scaled {
  double a, b, s, theta;
};

Scaled scaled(double kappa, const Vec3& p) {
  Scaled v;
  v.a = kappa * p.x();
  v.b = 1.0 - kappa * p.y();
  v.s = std::sqrt(v.a * v.a + v.b * v.b);  // b is near 1: no overflow, no need for hypot
  v.theta = polynomial_atan2(v.a, v.b);    // glibc's atan2 was 10% of a capsule step
  return v;
}

Vec3 rest_point(double kappa, const Vec3& p, const Scaled& v) {
  const double qy = (2.0 * p.y() - kappa * (p.x() * p.x() + p.y() * p.y())) / (1.0 + v.s);
  return {v.theta / kappa, qy, p.z()};
}

// d q / d p from da = kappa dp.x, db = -kappa dp.y, d theta = (b da - a db) / s^2 and
// ds = (a da + b db) / s:  dqx/dpx = b/s^2, dqx/dpy = a/s^2, dqy/dpx = -a/s, dqy/dpy = b/s.
Mat3 rest_jacobian(const Scaled& v) {
  const double s2 = v.s * v.s;
  Mat3 J;
  J << v.b / s2, v.a / s2, 0.0,    //
      -v.a / v.s, v.b / v.s, 0.0,  //
      0.0, 0.0, 1.0;
  return J;
}

}  // namespace

Vec3 BendMap::to_rest(const Vec3& p) const {
  if (is_identity()) return p;
  return rest_point(kappa_, p, scaled(kappa_, p));
}

Vec3 BendMap::to_rest(const Vec3& p, Mat3& jacobian) const {
  if (is_identity()) {
    jacobian.setIdentity();
    return p;
  }
  const Scaled v = scaled(kappa_, p);
  jacobian = rest_jacobian(v);
  return rest_point(kappa_, p, v);
}

MapJet BendMap::to_rest_jet(const Vec3& p) const {
  MapJet jet;
  if (is_identity()) {
    jet.value = p;
    return jet;
  }
  const Scaled v = scaled(kappa_, p);
  jet.value = rest_point(kappa_, p, v);
  jet.jacobian = rest_jacobian(v);
  // Second derivatives: q.x = theta/kappa is harmonic in (p.x, p.y); q.y = (1 - s)/kappa.
  const double k = kappa_, a = v.a, b = v.b, s = v.s;
  const double s3 = s * s * s, s4 = s3 * s;
  Mat3& hx = jet.hessians[0];
  hx(0, 0) = -2.0 * k * a * b / s4;
  hx(1, 1) = -hx(0, 0);
  hx(0, 1) = hx(1, 0) = k * (b * b - a * a) / s4;
  Mat3& hy = jet.hessians[1];
  hy(0, 0) = -k * b * b / s3;
  hy(1, 1) = -k * a * a / s3;
  hy(0, 1) = hy(1, 0) = -k * a * b / s3;
  return jet;
}

Vec3 BendMap::to_world(const Vec3& q) const {
  if (is_identity()) return q;
  // theta = kappa q.x, rho = 1/kappa - q.y; p.x = rho sin(theta), p.y = 1/kappa - rho cos(theta),
  // rearranged without the 1/kappa - 1/kappa cancellation.
  const double theta = kappa_ * q.x();
  const double half = std::sin(0.5 * theta);
  const double px = (1.0 - kappa_ * q.y()) * std::sin(theta) / kappa_;
  const double py = 2.0 * half * half / kappa_ + q.y() * std::cos(theta);
  return {px, py, q.z()};
}

}  // namespace dynamesh
