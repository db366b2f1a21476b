// Small fixed-size linear algebra types used throughout the engine (Eigen, double precision).
#pragma once

#include <Eigen/Dense>

namespace dynamesh {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// Axis-aligned box; empty when min > max on any axis.
struct Box3 {
  Vec3 min{Vec3::Constant(1e300)};
  Vec3 max{Vec3::Constant(-1e300)};

  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return (min.array() > max.array()).any(); }
  // Closed box: a point on its boundary is contained, and boxes touching there overlap.
  bool contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  bool overlaps(const Box3& o) const {
    return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
  }
  Box3 grown(double margin) const {
    return {min - Vec3::Constant(margin), max + Vec3::Constant(margin)};
  }
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 size() const { return max - min; }
  double diagonal() const { return empty() ? 0.0 : size().norm(); }
};

}  // namespace dynamesh
