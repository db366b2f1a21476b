#include "core/surface/expression/expr_scene.h"

#include "core/surface/expression/expr_options.h"
#include "core/surface/expression/height_expression_surface.h"
#include "core/surface/expression/implicit_expression_surface.h"
#include "core/surface/expression/parametric_expression_surface.h"

namespace dynamesh {

std::unique_ptr<Surface> make_expr_scene(const TextOptions& options) {
  const ExprOptions o = parse_expr_options(options);
  switch (o.kind) {
    case ExprKind::kImplicit:
      return std::make_unique<ImplicitExpressionSurface>(o.formula, *o.bounds, o.base_mesh);
    case ExprKind::kHeight:
      return std::make_unique<HeightExpressionSurface>(o.formula, *o.domain_min, *o.domain_max);
    case ExprKind::kParametric: {
      ParameterDomain domain;
      domain.min = *o.domain_min;
      domain.max = *o.domain_max;
      domain.periodic_u = o.periodic_u;
      domain.periodic_v = o.periodic_v;
      return std::make_unique<ParametricExpressionSurface>(o.formula, domain);
    }
  }
  return nullptr;
}

}  // namespace dynamesh
