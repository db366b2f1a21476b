#include "core/surface/expression/height_expression_surface.h"

#include <stdexcept>

#include "core/mesh/base_meshes.h"
#include "core/surface/expression/formula_checks.h"
#include "core/surface/finite_differences.h"

namespace dynamesh {

namespace {

constexpr int kScan = 33;      // grid points per side of the set_time() scan (~1000 evaluations)
constexpr int kBaseQuads = 8;  // base grid, as for the sinc scene

// (u, v) = (z, x) (header): the formula's arguments and the point for a parameter pair.
Vec2 xz(const Vec2& uv) {
  return {uv.y(), uv.x()};
}
Vec3 point(const Vec2& uv, double y) {
  return {uv.y(), y, uv.x()};
}

}  // namespace

HeightExpressionSurface::HeightExpressionSurface(const std::string& formula, const Vec2& domain_min,
                                                 const Vec2& domain_max)
    : formula_(formula),
      f_({formula}, {"x", "z", "t"}, "height formula"),
      tape_(f_.tape_with("t", 0.0)) {
  if (!(domain_min.array() < domain_max.array()).all() || !(domain_max - domain_min).allFinite())
    throw std::invalid_argument(
        "--domain is empty or not finite: expected xmin < xmax, zmin < zmax");
  domain_.min = xz(domain_min);  // xz() swaps the pair either way
  domain_.max = xz(domain_max);
  bounds_ = scan(0.0);
}

Box3 HeightExpressionSurface::scan(double t) const {
  Box3 box = scan_parametric(
      [&](const Vec2& uv) {
        const double x[3] = {uv.y(), uv.x(), t};
        return point(uv, f_.value(x));
      },
      "height formula '" + formula_ + "'", domain_, t, kScan);
  // The scan sees grid points only; a margin of a tenth of the height range (and of the
  // domain's size for a flat field) keeps the box conservative for smooth formulas.
  const double margin = 0.1 * std::max(box.size().y(), 1e-3 * (domain_.max - domain_.min).norm());
  box.min.y() -= margin;
  box.max.y() += margin;
  return box;
}

void HeightExpressionSurface::set_time(double t) {
  const Box3 box = scan(t);  // throws before anything changes
  bounds_ = box;
  Surface::set_time(t);
  tape_ = f_.tape_with("t", t);
}

Vec3 HeightExpressionSurface::position(const Vec2& uv) const {
  const double x[3] = {uv.y(), uv.x(), time()};
  if (tape_) {
    ForwardJet<0, 0> f[FormulaTape::kLocalStack];
    tape_->evaluate<0, 0>(x, f);
    return point(uv, f[0].value);
  }
  return point(uv, f_.value(x));
}

ParametricDerivatives HeightExpressionSurface::derivatives(const Vec2& uv) const {
  const double t = time();
  if (tape_) {
    const double x[3] = {uv.y(), uv.x(), t};
    ForwardJet<2, 2> jets[FormulaTape::kLocalStack];
    tape_->evaluate<2, 2>(x, jets);
    const ForwardJet<2, 2>& f = jets[0];  // derivatives in (x, z) = (v, u)
    ParametricDerivatives d;
    d.s = point(uv, f.value);
    d.su = Vec3(0.0, f.grad[1], 1.0);
    d.sv = Vec3(1.0, f.grad[0], 0.0);
    d.suu = Vec3(0.0, f.hessian(1, 1), 0.0);
    d.suv = Vec3(0.0, f.hessian(0, 1), 0.0);
    d.svv = Vec3(0.0, f.hessian(0, 0), 0.0);
    return d;
  }
  ParametricDerivatives d = parametric_differences(
      [&](const Vec2& q) {
        const double x[3] = {q.y(), q.x(), t};
        return point(q, f_.value(x));
      },
      uv, domain_.max - domain_.min);
  // z = u and x = v exactly; the quotients above carry rounding there.
  d.su.x() = 0.0, d.su.z() = 1.0, d.sv.x() = 1.0, d.sv.z() = 0.0;
  d.suu.x() = d.suu.z() = d.suv.x() = d.suv.z() = d.svv.x() = d.svv.z() = 0.0;
  return d;
}

Mesh48 HeightExpressionSurface::base_mesh() const {
  Mesh48 mesh = make_grid_mesh(kBaseQuads, kBaseQuads, domain_.min, domain_.max);
  for (const Vertex v : mesh.live_vertices()) mesh.position(v) = position(mesh.uv(v));
  return mesh;
}

}  // namespace dynamesh
