// A closed surface typed as a formula: {p : F(x, y, z, t) = 0} with F < 0 inside, inside a
// user-given box (--implicit EXPR --bounds ...). The base mesh is a box of quads placed on the
// surface by rays from an interior point when the surface is star-shaped around it; otherwise
// F's zero set contoured on a coarse grid and paired into quads (any genus, any number of
// components; core/topology/contour_base_mesh.h); or a user's mesh of the surface's topology
// (--base-mesh FILE) made 4-8 and projected.
// Values and derivatives come from the formula's tape with t fixed at the surface's time
// (rebuilt at every set_time(), so that terms in t alone are computed once per frame), on
// jets: exact gradients and Hessians. A formula without a tape (Expression::differentiable())
// uses muparser and central differences with steps relative to the box's diagonal.
//
// Guards (formula_checks.h): the formula is scanned over the box when built and at every
// set_time(), which throws before the time changes, so the adapter keeps its last good mesh.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/surface/expression/expression.h"
#include "core/surface/expression/triangle_mesh_file.h"
#include "core/surface/surface.h"

namespace dynamesh {

class ImplicitExpressionSurface final : public ImplicitSurface {
 public:
  // Throws std::invalid_argument for a bad formula, bad bounds, a bad base mesh file, or a
  // surface that fails the guards or whose base mesh does not project at t = 0.
  ImplicitExpressionSurface(const std::string& formula, const Box3& bounds,
                            const std::string& base_mesh_path = "");

  std::string name() const override { return "expr"; }
  void set_time(double t) override;
  Box3 bounds() const override { return bounds_; }
  Mesh48 base_mesh() const override;
  // A typed formula may change topology unless the user's base mesh fixes it.
  bool may_change_topology() const override { return !file_mesh_; }

  double value(const Vec3& p) const override;
  double value_gradient(const Vec3& p, Vec3& gradient) const override;
  Mat3 hessian(const Vec3& p) const override;

  const std::string& formula() const { return formula_; }

 private:
  Mesh48 build_base_mesh() const;
  Mesh48 box_base_mesh() const;
  Mesh48 file_base_mesh() const;
  bool is_star_shaped() const;
  void check_orientation(const Mesh48& mesh, const std::string& source) const;

  std::string formula_;
  Expression f_;
  std::optional<FormulaTape> tape_;  // f_ at time(); empty when f_ is not differentiable
  Box3 bounds_;
  std::string base_mesh_path_;
  std::optional<TriangleMesh> file_mesh_;
  Vec3 interior_{Vec3::Zero()};         // F < 0 here at the current time
  std::optional<Mesh48> base_at_zero_;  // built (and so validated) by the constructor
};

}  // namespace dynamesh
