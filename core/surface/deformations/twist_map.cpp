// With phi = -tau p.x, c = cos(phi), s = sin(phi):
//   q = (p.x, c p.y - s p.z, s p.y + c p.z),
// and since d phi/d p.x = -tau, d(q.y, q.z)/d p.x = tau (q.z, -q.y); differentiating once more
// gives the second derivatives below (all involve p.x).
#include "core/surface/deformations/twist_map.h"

#include <cmath>

namespace dynamesh {

namespace {

Vec3 rotate(double c, double s, const Vec3& p) {
  return {p.x(), c * p.y() - s * p.z(), s * p.y() + c * p.z()};
}

Mat3 jacobian_at(double tau, double c, double s, const Vec3& q) {
  Mat3 J;
  J << 1.0, 0.0, 0.0,      //
      tau * q.z(), c, -s,  //
      -tau * q.y(), s, c;
  return J;
}

}  // namespace

Vec3 TwistMap::to_rest(const Vec3& p) const {
  const double phi = -tau_ * p.x();
  return rotate(std::cos(phi), std::sin(phi), p);
}

Vec3 TwistMap::to_rest(const Vec3& p, Mat3& jacobian) const {
  const double phi = -tau_ * p.x();
  const double c = std::cos(phi), s = std::sin(phi);
  const Vec3 q = rotate(c, s, p);
  jacobian = jacobian_at(tau_, c, s, q);
  return q;
}

MapJet TwistMap::to_rest_jet(const Vec3& p) const {
  const double phi = -tau_ * p.x();
  const double c = std::cos(phi), s = std::sin(phi);
  MapJet jet;
  jet.value = rotate(c, s, p);
  jet.jacobian = jacobian_at(tau_, c, s, jet.value);
  const double t = tau_, t2 = tau_ * tau_;
  Mat3& hy = jet.hessians[1];
  hy(0, 0) = -t2 * jet.value.y();
  hy(0, 1) = hy(1, 0) = t * s;
  hy(0, 2) = hy(2, 0) = t * c;
  Mat3& hz = jet.hessians[2];
  hz(0, 0) = -t2 * jet.value.z();
  hz(0, 1) = hz(1, 0) = -t * c;
  hz(0, 2) = hz(2, 0) = t * s;
  return jet;
}

Vec3 TwistMap::to_world(const Vec3& q) const {
  // to_rest keeps x, so the inverse rotates back by the angle at that same x.
  const double phi = tau_ * q.x();
  return rotate(std::cos(phi), std::sin(phi), q);
}

}  // namespace dynamesh
