#include "core/surface/expression/expr_options.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "core/surface/expression/expression.h"

namespace dynamesh {

namespace {

const char* kUsage =
    "the expr scene needs one of --implicit \"F(x,y,z,t)\" --bounds "
    "xmin,ymin,zmin,xmax,ymax,zmax | --height \"f(x,z,t)\" [--domain xmin,xmax,zmin,zmax] | "
    "--parametric \"X;Y;Z\" (in u,v,t) --domain umin,umax,vmin,vmax [--periodic u|v|uv]";

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

std::vector<double> parse_number_list(const std::string& text, std::size_t count,
                                      const std::string& option, const std::string& format) {
  std::vector<double> numbers;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item = trimmed(text.substr(start, comma - start));
    char* end = nullptr;
    double x = std::strtod(item.c_str(), &end);
    // Not a plain number: a constant formula such as 2*pi.
    if (!item.empty() && *end != '\0') {
      try {
        x = Expression({item}, {}, option).value({});
        end = nullptr;
      } catch (const std::invalid_argument&) {
      }
    }
    if (item.empty() || (end && *end != '\0') || !std::isfinite(x))
      throw std::invalid_argument(option + " expects " + format + " (finite numbers), got '" +
                                  text + "'");
    numbers.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (numbers.size() != count)
    throw std::invalid_argument(option + " expects " + std::to_string(count) + " numbers, " +
                                format + ", got " + std::to_string(numbers.size()) + " in '" +
                                text + "'");
  return numbers;
}

ExprOptions parse_expr_options(const TextOptions& options) {
  ExprOptions o;
  int kinds = 0;
  bool periodic_given = false;
  for (const auto& [key, value] : options) {
    if (key == "implicit" || key == "height" || key == "parametric") {
      if (++kinds > 1)
        throw std::invalid_argument(
            "expr: give only one of --implicit, --height, --parametric (got more than one)");
      o.kind = key == "implicit" ? ExprKind::kImplicit
               : key == "height" ? ExprKind::kHeight
                                 : ExprKind::kParametric;
      o.formula = value;
    } else if (key == "bounds") {
      const auto b = parse_number_list(value, 6, "--bounds", "xmin,ymin,zmin,xmax,ymax,zmax");
      o.bounds = Box3{Vec3(b[0], b[1], b[2]), Vec3(b[3], b[4], b[5])};
      for (int a = 0; a < 3; ++a)
        if (!(b[a] < b[a + 3]))
          throw std::invalid_argument("--bounds " + value + " is empty along " +
                                      std::string(1, "xyz"[a]) +
                                      ": each minimum must be below its maximum");
    } else if (key == "domain") {
      const auto d = parse_number_list(value, 4, "--domain", "min1,max1,min2,max2");
      if (!(d[0] < d[1]) || !(d[2] < d[3]))
        throw std::invalid_argument("--domain " + value +
                                    " is empty: expected min1,max1,min2,max2 with min < max");
      o.domain_min = Vec2(d[0], d[2]);
      o.domain_max = Vec2(d[1], d[3]);
    } else if (key == "periodic") {
      periodic_given = true;
      if (value != "u" && value != "v" && value != "uv" && value != "vu" && value != "none")
        throw std::invalid_argument("--periodic expects u, v, uv or none, got '" + value + "'");
      o.periodic_u = value.find('u') != std::string::npos;
      o.periodic_v = value.find('v') != std::string::npos;
    } else if (key == "base-mesh") {
      if (value.empty()) throw std::invalid_argument("--base-mesh expects a file name");
      o.base_mesh = value;
    } else {
      throw std::invalid_argument("expr: takes no option '" + key + "'; " + kUsage);
    }
  }
  // No options at all: the default formula, so that a scene menu (and `--scene expr` alone)
  // shows something to start editing from. Options without a formula are a mistake.
  if (options.empty()) {
    o.formula = kDefaultImplicitFormula;
    o.bounds = Box3{Vec3::Constant(-1.5), Vec3::Constant(1.5)};
    return o;
  }
  if (kinds == 0) throw std::invalid_argument(std::string("expr: no formula given; ") + kUsage);
  switch (o.kind) {
    case ExprKind::kImplicit:
      if (!o.bounds)
        throw std::invalid_argument(
            "--implicit needs --bounds xmin,ymin,zmin,xmax,ymax,zmax: a box that contains the "
            "surface (F > 0 on its sides)");
      if (o.domain_min)
        throw std::invalid_argument(
            "--domain is for --height and --parametric; "
            "--implicit takes --bounds");
      if (periodic_given) throw std::invalid_argument("--periodic is for --parametric only");
      break;
    case ExprKind::kHeight:
      if (o.bounds)
        throw std::invalid_argument(
            "--bounds is for --implicit; --height takes "
            "--domain xmin,xmax,zmin,zmax");
      if (periodic_given) throw std::invalid_argument("--periodic is for --parametric only");
      if (!o.base_mesh.empty()) throw std::invalid_argument("--base-mesh is for --implicit only");
      if (!o.domain_min) o.domain_min = Vec2(-1.0, -1.0), o.domain_max = Vec2(1.0, 1.0);
      break;
    case ExprKind::kParametric:
      if (o.bounds)
        throw std::invalid_argument(
            "--bounds is for --implicit; --parametric takes "
            "--domain umin,umax,vmin,vmax");
      if (!o.base_mesh.empty()) throw std::invalid_argument("--base-mesh is for --implicit only");
      if (!o.domain_min)
        throw std::invalid_argument(
            "--parametric needs --domain umin,umax,vmin,vmax (e.g. 0,2*pi,-1,1 with "
            "--periodic u for a cylinder)");
      break;
  }
  return o;
}

}  // namespace dynamesh
