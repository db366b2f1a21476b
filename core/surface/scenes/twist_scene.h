// Scene `twist` (SCENES.md; de Goes et al. 2006, Section 4.4): a bar with an Lp cross-section
// and superelliptic ends (shapes/lp_bar.h), twisted about x at the rate
// tau(t) = t * turns * 2 pi / (2h) radians per unit length (turns = 1.5: one and a half turns
// over the bar at t = 1). F(p) = F0(q(p)) with the twist p -> q (deformations/twist_map.h).
#pragma once

#include <string>
#include <vector>

#include "core/surface/deformations/twist_map.h"
#include "core/surface/shapes/lp_bar.h"
#include "core/surface/surface.h"

namespace dynamesh {

class TwistScene final : public ImplicitSurface {
 public:
  static constexpr const char* kName = "twist";
  static constexpr const char* kDescription =
      "implicit bar of Lp cross-section twisted by up to `turns` turns (paper 4.4)";

  struct Params {
    double h = 1.5;
    double r = 0.4;
    double p = 4.0;
    double s = 8.0;
    double turns = 1.5;
  };

  TwistScene();

  std::string name() const override { return kName; }
  void set_time(double t) override;
  std::vector<SurfaceParameter> parameters() const override;
  void set_parameter(const std::string& name, double value) override;
  Box3 bounds() const override;
  double length_scale() const override { return scale_; }
  Mesh48 base_mesh() const override;
  // The untwisted bar. Refined directly at a strong twist, the twisted box base mesh does not
  // give an embedded mesh (3 turns, t = 1, T = 0.002: 1.67M self-intersecting triangle pairs,
  // smallest angle 0.72 degrees); the adapter starts here instead and follows the twist.
  double mild_time() const override { return 0.0; }

  double value(const Vec3& p) const override;
  double value_gradient(const Vec3& p, Vec3& gradient) const override;
  Mat3 hessian(const Vec3& p) const override;
  double value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const override;

  const LpBar& rest_shape() const { return bar_; }
  // No rest map for the adapter (ImplicitSurface::has_rest_map), because no transport that
  // follows this material can be shear-free: the twist's own strain of the bar's sides is a
  // shear (between cross-sections dx apart the side turns by tau dx, so a patch at radius rho
  // shears by tau' rho per unit time), and vertices carried with the material shear their
  // triangles with it (measured with smoothing: worst aspect ratio 4.7 -> 17.7, smallest angle
  // 16.6 -> 7.3 deg over a 0 -> 1 run). Correction along the normal is the shear-free
  // transport: each vertex keeps its x and moves within its own cross-section's plane onto the
  // turned section, the bar sliding under it; its sweeps return to the same mesh. What it
  // cannot do alone is follow a fast twist in one step (3 turns in 10 steps folded the mesh):
  // the adapter's sub-steps (core/adapt/motion_substeps.h) bound each step's edge strain.

  const TwistMap& twist() const { return twist_; }

  // The twist turns each cross-section within its plane x = const, so smoothing moves each
  // vertex within that plane too (ImplicitSurface::invariant_axis). Otherwise the
  // twisted sides' diagonal principal directions steer Equation 1's moves along the bar, the
  // vertices come back from a sweep displaced along x, and the hierarchy keeps the refinement
  // that placement needs: 0.25 <-> 1 sweeps at T = 0.008 returned 0.95, 1.04, 1.02, 1.06, 1.07,
  // 1.08 times the first count; keeping x, 0.98, 0.96, 0.94, 0.98, 0.97, 0.96.
  Vec3 invariant_axis() const override { return Vec3::UnitX(); }

 private:
  void update();

  Params params_;
  LpBar bar_;
  TwistMap twist_;
  double scale_ = 1.0;
};

}  // namespace dynamesh
