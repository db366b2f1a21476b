// Scene `sphere` (SCENES.md; de Goes et al. 2006, Section 4.3): a sphere whose radius grows
// geometrically from R0 to R1, F(p) = |p| - R(t), R(t) = R0 (R1/R0)^t. The scene also carries
// the target edge length L of its multi-criteria adaptation (geometric error on x < 0, edge
// length on x >= 0), read by the adapter.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

class SphereScene final : public ImplicitSurface {
 public:
  static constexpr const char* kName = "sphere";
  static constexpr const char* kDescription =
      "implicit sphere growing from radius R0 to R1 (paper 4.3, multi-criteria)";

  struct Params {
    double R0 = 0.6;
    double R1 = 9.0;
    double L = 0.25;
  };

  SphereScene();

  std::string name() const override { return kName; }
  void set_time(double t) override;
  std::vector<SurfaceParameter> parameters() const override;
  void set_parameter(const std::string& name, double value) override;
  Box3 bounds() const override;
  double length_scale() const override { return 2.0 * std::sqrt(3.0) * radius_; }
  Mesh48 base_mesh() const override;

  double value(const Vec3& p) const override { return p.norm() - radius_; }
  double value_gradient(const Vec3& p, Vec3& gradient) const override;
  Mat3 hessian(const Vec3& p) const override;

  double radius() const { return radius_; }
  // Target edge length on the half x >= 0.
  double edge_length() const { return params_.L; }

 private:
  void update();

  Params params_;
  double radius_ = 0.6;
};

}  // namespace dynamesh
