// Scene `blobs` (SCENES.md; issue 16): two Gaussian blobs that approach, merge and separate
// again, a surface whose topology changes twice:
//   F(p, t) = tau - exp(-|p - c1|^2 / s^2) - exp(-|p - c2|^2 / s^2),   F < 0 inside,
//   c1 = (a(t), 0, 0), c2 = (-a(t), 0, 0),   a(t) = a_near + (a_far - a_near) (2t - 1)^2.
// They touch when a = s sqrt(ln(2 / tau)) (0.589 by default: t = 0.151 and 0.849): two
// components (chi = 4) before and after, one (chi = 2) between. The base mesh is contoured
// from F (core/topology/contour_base_mesh.h), so it has whichever topology F has at the time.
#pragma once

#include <string>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

class BlobsScene final : public ImplicitSurface {
 public:
  static constexpr const char* kName = "blobs";
  static constexpr const char* kDescription =
      "two Gaussian blobs that merge and separate again (topology change)";

  struct Params {
    double tau = 0.5;
    double s = 0.5;
    double a_near = 0.2;
    double a_far = 1.0;
  };

  BlobsScene() = default;

  std::string name() const override { return kName; }
  void set_time(double t) override;
  std::vector<SurfaceParameter> parameters() const override;
  void set_parameter(const std::string& name, double value) override;
  Box3 bounds() const override;
  Mesh48 base_mesh() const override;
  bool may_change_topology() const override { return true; }

  double value(const Vec3& p) const override;
  double value_gradient(const Vec3& p, Vec3& gradient) const override;
  Mat3 hessian(const Vec3& p) const override;

  // Half the distance between the centres at the current time.
  double separation() const { return a_; }
  // a(t) as SCENES.md gives it.
  static double separation_at(const Params& p, double t);

 private:
  Params params_;
  double a_ = separation_at(Params{}, 0.0);
};

}  // namespace dynamesh
