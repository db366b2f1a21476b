// Scene `capsule-bend` (SCENES.md; de Goes et al. 2006, Section 4.1): a capsule of half-length h
// and radius r along x, bent about the z axis by a total angle Theta(t) = bend * t, i.e. with
// curvature kappa = Theta / (2h) along its axis. F(p) = F0(q(p)) with the capsule's signed
// distance F0 (shapes/capsule.h) and the bend p -> q (deformations/bend_map.h).
#pragma once

#include <string>
#include <vector>

#include "core/surface/deformations/bend_map.h"
#include "core/surface/shapes/capsule.h"
#include "core/surface/surface.h"

namespace dynamesh {

class CapsuleBendScene final : public ImplicitSurface {
 public:
  static constexpr const char* kName = "capsule-bend";
  static constexpr const char* kDescription =
      "implicit capsule (cylinder with round caps) bent by up to `bend` radians (paper 4.1)";

  struct Params {
    double h = 1.5;
    double r = 0.4;
    double bend = 3.14159265358979323846;
  };

  CapsuleBendScene();

  std::string name() const override { return kName; }
  void set_time(double t) override;
  std::vector<SurfaceParameter> parameters() const override;
  // Besides each range, rejects (unchanged) combinations that fold the capsule onto itself
  // at t = 1: the inner side must stay off the bending axis (bend < 2h/r) and the two caps
  // must not meet (bend (h + r) / (2h) < pi).
  void set_parameter(const std::string& name, double value) override;
  Box3 bounds() const override;
  double length_scale() const override { return scale_; }
  Mesh48 base_mesh() const override;

  double value(const Vec3& p) const override;
  double value_gradient(const Vec3& p, Vec3& gradient) const override;
  Mat3 hessian(const Vec3& p) const override;
  double value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const override;

  // The bend is nearly isometric (it keeps arc length along the axis): vertices carried with
  // it keep their triangles' shape, and the refinement at the rotating caps moves with them.
  // Corrected along the normal only, the caps slid under their vertices and the mesh grew by
  // about 5% with every bend cycle (1.55x after 12; 1.14x with the transport).
  bool has_rest_map() const override { return true; }
  Vec3 to_rest(const Vec3& p) const override { return bend_.to_rest(p); }
  Vec3 from_rest(const Vec3& q) const override { return bend_.to_world(q); }

  const Capsule& rest_shape() const { return capsule_; }
  const BendMap& bend() const { return bend_; }

 private:
  void update();

  Params params_;
  Capsule capsule_;
  BendMap bend_;
  double scale_ = 1.0;
};

}  // namespace dynamesh
