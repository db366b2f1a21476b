// The text options of the `expr` scene (what dynamesh-cli's --implicit, --height,
// --parametric, --bounds, --domain, --periodic and --base-mesh pass through make_scene), read
// and checked: exactly one kind of formula, and only the options that kind takes.
#pragma once

#include <optional>
#include <string>

#include "core/geometry/vector_types.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {

enum class ExprKind { kImplicit, kHeight, kParametric };

struct ExprOptions {
  ExprKind kind = ExprKind::kImplicit;
  std::string formula;                          // as typed; "X;Y;Z" for kParametric
  std::optional<Box3> bounds;                   // --bounds xmin,ymin,zmin,xmax,ymax,zmax (implicit)
  std::optional<Vec2> domain_min, domain_max;   // --domain a,b,c,d: [a, b] x [c, d]
  bool periodic_u = false, periodic_v = false;  // --periodic u|v|uv (parametric)
  std::string base_mesh;                        // --base-mesh FILE (implicit)
};

// Without any option: a pulsing blob in the bounds [-1.5, 1.5]^3.
inline constexpr const char* kDefaultImplicitFormula =
    "sqrt(x^2+y^2+z^2) - 0.8*(1 + 0.3*sin(2*pi*t)*sin(4*x)*sin(4*y)*sin(4*z))";

// Throws std::invalid_argument (one line: what is wrong, what to type instead).
ExprOptions parse_expr_options(const TextOptions& options);

// "a,b,c" -> exactly `count` finite numbers; `option` and `format` name them in errors.
std::vector<double> parse_number_list(const std::string& text, std::size_t count,
                                      const std::string& option, const std::string& format);

}  // namespace dynamesh
