// Scene `expr` (issue 8): a surface the user types. Built from the text options of
// expr_options.h: --implicit F(x,y,z,t) --bounds ... [--base-mesh FILE] (closed, F < 0 inside),
// --height f(x,z,t) [--domain ...] (open height field), or --parametric "X;Y;Z" (u, v, t)
// --domain ... [--periodic u|v|uv].
#pragma once

#include <memory>

#include "core/surface/scene_registry.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct ExprScene {
  static constexpr const char* kName = "expr";
  static constexpr const char* kDescription =
      "a typed surface: --implicit F(x,y,z,t) --bounds ... [--base-mesh FILE] | --height "
      "f(x,z,t) [--domain ...] | --parametric \"X;Y;Z\" (u,v,t) --domain ... [--periodic u|v|uv]";
};

// Throws std::invalid_argument (one line) for bad options, formulas or base meshes.
std::unique_ptr<Surface> make_expr_scene(const TextOptions& options);

}  // namespace dynamesh
