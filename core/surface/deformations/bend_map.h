// The bend of the capsule-bend scene (SCENES.md; de Goes et al. 2006, Section 4.1): the rest
// x axis is wrapped onto a circle of curvature kappa about an axis parallel to z through
// (0, 1/kappa, 0), arc length preserved along the axis. to_rest() is SCENES.md's map p -> q
// and to_world() its inverse.
#pragma once

#include <cmath>

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"

namespace dynamesh {

class BendMap {
 public:
  // Below this curvature the map is the identity (SCENES.md).
  static constexpr double kMinCurvature = 1e-9;

  explicit BendMap(double kappa = 0.0) : kappa_(kappa) {}
  double curvature() const { return kappa_; }
  bool is_identity() const { return !(std::abs(kappa_) > kMinCurvature); }

  Vec3 to_rest(const Vec3& p) const;
  Vec3 to_rest(const Vec3& p, Mat3& jacobian) const;
  MapJet to_rest_jet(const Vec3& p) const;
  // Inverse of to_rest for rest points with q.y < 1/kappa and |kappa q.x| < pi.
  Vec3 to_world(const Vec3& q) const;

 private:
  double kappa_;
};

}  // namespace dynamesh
