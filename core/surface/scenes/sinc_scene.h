// Scene `sinc` (SCENES.md; de Goes et al. 2006, Section 4.2, Equation 2): the height field
//   y = alpha(t) sinc(beta r) exp(kappa r),  r = sqrt(x^2 + z^2),  alpha(t) = alpha sin(2 pi t)
// over the parameter square (u, v) = (z, x) in [-1, 1]^2: S(u, v) = (v, y, u). The axes are
// taken in this order so that the normal Su x Sv = (-y_x, 1, -y_z) points up (+y): the upper
// side of the open sheet is its front, and the grid base mesh (counter-clockwise in (u, v))
// turns the same way. The mesh is open, its boundary on the square's boundary.
//
// Note: the profile's slope at r = 0 is alpha(t) kappa, not 0, so for alpha(t) kappa != 0 the
// centre is the tip of a cone: the surface is not differentiable there. derivatives() returns
// the symmetric choice at r = 0 exactly (zero slope, second derivatives f''(0) in every
// direction); curvature there is a convention, not a limit.
#pragma once

#include <string>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

class SincScene final : public ParametricSurface {
 public:
  static constexpr const char* kName = "sinc";
  static constexpr const char* kDescription =
      "parametric height field alpha sin(2 pi t) sinc(beta r) exp(kappa r) (paper 4.2, Eq. 2)";

  struct Params {
    double alpha = 0.6;
    double beta = 4.0 * 3.14159265358979323846;
    double kappa = -0.5;
  };

  // The radial profile f(r) = alpha(t) sinc(beta r) exp(kappa r) and its first two
  // derivatives.
  struct Profile {
    double f, df, d2f;
  };

  SincScene();

  std::string name() const override { return kName; }
  void set_time(double t) override;
  std::vector<SurfaceParameter> parameters() const override;
  void set_parameter(const std::string& name, double value) override;
  Box3 bounds() const override;
  Mesh48 base_mesh() const override;

  ParameterDomain domain() const override;
  Vec3 position(const Vec2& uv) const override;
  ParametricDerivatives derivatives(const Vec2& uv) const override;

  Profile profile(double r) const;
  // alpha(t) = alpha sin(2 pi t).
  double amplitude() const { return amplitude_; }

 private:
  void update();

  Params params_;
  double amplitude_ = 0.0;
};

}  // namespace dynamesh
