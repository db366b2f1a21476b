#include "core/surface/expression/parametric_expression_surface.h"

#include <stdexcept>

#include "core/surface/expression/formula_checks.h"
#include "core/surface/expression/periodic_grid_mesh.h"
#include "core/surface/finite_differences.h"

namespace dynamesh {

namespace {

constexpr int kScan = 33;
constexpr int kBaseQuads = 8;  // even: a periodic direction needs an even count

}  // namespace

std::vector<std::string> split_parametric_formulas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t semicolon = text.find(';', start);
    parts.push_back(text.substr(start, semicolon - start));
    if (semicolon == std::string::npos) break;
    start = semicolon + 1;
  }
  if (parts.size() != 3)
    throw std::invalid_argument(
        "--parametric expects three formulas \"X;Y;Z\" in u, v, t "
        "separated by ';', got " +
        std::to_string(parts.size()) + " in '" + text + "'");
  return parts;
}

ParametricExpressionSurface::ParametricExpressionSurface(const std::string& formulas,
                                                         const ParameterDomain& domain)
    : text_(formulas),
      xyz_(split_parametric_formulas(formulas), {"u", "v", "t"}, "parametric formula"),
      tape_(xyz_.tape_with("t", 0.0)),
      domain_(domain) {
  if (!(domain_.min.array() < domain_.max.array()).all() ||
      !(domain_.max - domain_.min).allFinite())
    throw std::invalid_argument(
        "--domain is empty or not finite: expected umin < umax, vmin < vmax");
  bounds_ = scan(0.0);
}

Vec3 ParametricExpressionSurface::evaluate(const Vec2& uv, double t) const {
  const double in[3] = {uv.x(), uv.y(), t};
  Vec3 out;
  xyz_.evaluate(in, std::span<double>(out.data(), 3));
  return out;
}

Box3 ParametricExpressionSurface::scan(double t) const {
  return scan_parametric([&](const Vec2& uv) { return evaluate(uv, t); },
                         "parametric formula '" + text_ + "'", domain_, t, kScan);
}

void ParametricExpressionSurface::set_time(double t) {
  const Box3 box = scan(t);  // throws before anything changes
  bounds_ = box;
  Surface::set_time(t);
  tape_ = xyz_.tape_with("t", t);
}

Vec3 ParametricExpressionSurface::position(const Vec2& uv) const {
  if (tape_) {
    const double in[3] = {uv.x(), uv.y(), time()};
    ForwardJet<0, 0> s[FormulaTape::kLocalStack];
    tape_->evaluate<0, 0>(in, s);
    return {s[0].value, s[1].value, s[2].value};
  }
  return evaluate(uv, time());
}

ParametricDerivatives ParametricExpressionSurface::derivatives(const Vec2& uv) const {
  const double t = time();
  if (tape_) {
    const double in[3] = {uv.x(), uv.y(), t};
    ForwardJet<2, 2> s[FormulaTape::kLocalStack];
    tape_->evaluate<2, 2>(in, s);
    ParametricDerivatives d;
    for (int k = 0; k < 3; ++k) {
      d.s[k] = s[k].value;
      d.su[k] = s[k].grad[0];
      d.sv[k] = s[k].grad[1];
      d.suu[k] = s[k].hessian(0, 0);
      d.suv[k] = s[k].hessian(0, 1);
      d.svv[k] = s[k].hessian(1, 1);
    }
    return d;
  }
  return parametric_differences([&](const Vec2& q) { return evaluate(q, t); }, uv,
                                domain_.max - domain_.min);
}

Mesh48 ParametricExpressionSurface::base_mesh() const {
  Mesh48 mesh = make_periodic_grid_mesh(kBaseQuads, kBaseQuads, domain_.min, domain_.max,
                                        domain_.periodic_u, domain_.periodic_v);
  for (const Vertex v : mesh.live_vertices()) mesh.position(v) = position(mesh.uv(v));
  return mesh;
}

}  // namespace dynamesh
