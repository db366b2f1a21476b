#include "core/surface/deformations/bend_map.h"

#include <cmath>

namespace dynamesh {

MapJet BendMap::to_rest_jet(const Vec3& p) const {
  MapJet jet;
  if (is_identity()) {
    jet.value = p;
    return jet;
  }
  using namespace bend_map_detail;
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
