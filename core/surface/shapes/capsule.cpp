#include "core/surface/shapes/capsule.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {

namespace {

// q - c(q): the offset from the nearest point of the segment.
Vec3 offset(const Capsule& c, const Vec3& q) {
  return {q.x() - std::clamp(q.x(), -c.half_length, c.half_length), q.y(), q.z()};
}

}  // namespace

double Capsule::value(const Vec3& q) const {
  return offset(*this, q).norm() - radius;
}

double Capsule::value_gradient(const Vec3& q, Vec3& gradient) const {
  const Vec3 d = offset(*this, q);
  const double dist = d.norm();
  // On the segment the distance has no gradient; zero tells projection to stop there.
  gradient = dist > 0.0 ? Vec3(d / dist) : Vec3::Zero();
  return dist - radius;
}

ScalarJet Capsule::jet(const Vec3& q) const {
  ScalarJet j;
  const Vec3 d = offset(*this, q);
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
