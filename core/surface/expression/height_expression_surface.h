// An open height field typed as a formula: y = f(x, z, t) over the domain [xmin, xmax] x
// [zmin, zmax] (--height EXPR --domain ...), as a parametric surface with (u, v) = (z, x):
// S(u, v) = (v, f(v, u, t), u), so the normal Su x Sv = (-f_x, 1, -f_z) points up (+y), as for
// the sinc scene: the upper side is the front, and the grid base mesh (counter-clockwise in
// (u, v)) agrees with it. domain() is [zmin, zmax] x [xmin, xmax] accordingly. Positions and
// derivatives come from the formula's tape with t fixed at the surface's time, on jets (exact);
// without a tape (Expression::differentiable()), from muparser and central differences with steps
// relative to the domain. bounds() comes from a grid scan at each set_time(), which also
// throws (before the time changes) where f is not finite.
#pragma once

#include <optional>
#include <string>

#include "core/surface/expression/expression.h"
#include "core/surface/surface.h"

namespace dynamesh {

class HeightExpressionSurface final : public ParametricSurface {
 public:
  HeightExpressionSurface(const std::string& formula, const Vec2& domain_min,
                          const Vec2& domain_max);

  std::string name() const override { return "expr"; }
  void set_time(double t) override;
  Box3 bounds() const override { return bounds_; }
  Mesh48 base_mesh() const override;

  ParameterDomain domain() const override { return domain_; }
  Vec3 position(const Vec2& uv) const override;
  ParametricDerivatives derivatives(const Vec2& uv) const override;

 private:
  Box3 scan(double t) const;

  std::string formula_;
  Expression f_;
  std::optional<FormulaTape> tape_;  // f_ at time(); empty when f_ is not differentiable
  ParameterDomain domain_;
  Box3 bounds_;
};

}  // namespace dynamesh
