// The twist of the twist scene (SCENES.md; de Goes et al. 2006, Section 4.4): the cross-section
// at abscissa x is turned about the x axis by tau * x. to_rest() is SCENES.md's map p -> q
// (rotation by phi = -tau p.x of (p.y, p.z)) and to_world() its inverse.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/jet.h"

namespace dynamesh {

class TwistMap {
 public:
  explicit TwistMap(double tau = 0.0) : tau_(tau) {}
  double rate() const { return tau_; }

  Vec3 to_rest(const Vec3& p) const;
  Vec3 to_rest(const Vec3& p, Mat3& jacobian) const;
  MapJet to_rest_jet(const Vec3& p) const;
  Vec3 to_world(const Vec3& q) const;

 private:
  double tau_;
};

}  // namespace dynamesh
