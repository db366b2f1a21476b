// A parametric surface typed as three formulas "X; Y; Z" in u, v and t over a rectangular
// domain (--parametric "X;Y;Z" --domain umin,umax,vmin,vmax [--periodic u|v|uv]). Periodic
// directions close up: the base mesh is a periodic grid (periodic_grid_mesh.h) whose seam
// vertices are shared, so a cylinder (u periodic) has boundary only at its two ends and a
// torus (u and v) none; the adapter interpolates (u, v) across the seam. Orientation follows
// Su x Sv. Positions and derivatives come from the formulas' tape with t fixed at the
// surface's time, on jets (exact); without a tape (Expression::differentiable()), from
// muparser and central differences with steps relative to the domain. A grid scan at
// construction and at every set_time() (which throws before the time changes) checks that S
// is finite and closes up along periodic directions, and gives bounds().
#pragma once

#include <optional>
#include <string>

#include "core/surface/expression/expression.h"
#include "core/surface/surface.h"

namespace dynamesh {

class ParametricExpressionSurface final : public ParametricSurface {
 public:
  // `formulas` = "X;Y;Z".
  ParametricExpressionSurface(const std::string& formulas, const ParameterDomain& domain);

  std::string name() const override { return "expr"; }
  void set_time(double t) override;
  Box3 bounds() const override { return bounds_; }
  Mesh48 base_mesh() const override;

  ParameterDomain domain() const override { return domain_; }
  Vec3 position(const Vec2& uv) const override;
  ParametricDerivatives derivatives(const Vec2& uv) const override;

 private:
  Box3 scan(double t) const;
  Vec3 evaluate(const Vec2& uv, double t) const;

  std::string text_;
  Expression xyz_;
  std::optional<FormulaTape> tape_;  // xyz_ at time(); empty when xyz_ is not differentiable
  ParameterDomain domain_;
  Box3 bounds_;
};

// "X;Y;Z" -> {X, Y, Z}; throws std::invalid_argument unless there are exactly three parts.
std::vector<std::string> split_parametric_formulas(const std::string& text);

}  // namespace dynamesh
