#include "core/surface/shapes/capsule.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {

double Capsule::value(const Vec3& q) const {
  return offset(q).norm() - radius;
}

ScalarJet Capsule::jet(const Vec3& q) const {
  ScalarJet j;
  const Vec3 d = offset(q);
  const double dist = d.norm();
  j.value = dist - radius;
  if (!(dist > 0.0)) return j;
  j.gradient = d / dist;
  // Hessian of the distance to a point (caps) or to a line (cylinder): the projector onto the
  // directions in which the nearest point stays put, minus the normal, over the distance.
  Mat3 P = Mat3::Identity();
  if (std::abs(q.x()) <= half_length) P(0, 0) = 0.0;
  j.hessian = (P - j.gradient * j.gradient.transpose()) / dist;
  return j;
}

Vec3 Capsule::closest_point(const Vec3& q) const {
  const Vec3 c(std::clamp(q.x(), -half_length, half_length), 0.0, 0.0);
  Vec3 d = q - c;
  if (!(d.norm() > 0.0)) d = Vec3::UnitY();
  return c + radius * d.normalized();
}

}  // namespace dynamesh
