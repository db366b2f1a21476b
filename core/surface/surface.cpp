// Default implementations of the Surface interface (surface.h): parameter errors, finite
// difference derivatives for surfaces without closed forms, and principal curvatures from
// derivatives (fundamental forms for parametric surfaces, Goldman 2005 for implicit ones).
#include "core/surface/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/surface/finite_differences.h"
#include "core/surface/parameter_table.h"
#include "core/surface/principal_frame.h"

namespace dynamesh {

// ---- Surface ------------------------------------------------------------------------------

void Surface::set_parameter(const std::string& name, double value) {
  const std::vector<SurfaceParameter> list = parameters();
  for (const SurfaceParameter& p : list) {
    if (p.name != name) continue;
    check_parameter_value(this->name(), p, value);
    throw std::invalid_argument(this->name() + ": parameter '" + name + "' is read-only");
  }
  throw std::invalid_argument(unknown_parameter_message(this->name(), name, list));
}

// ---- ParametricSurface ----------------------------------------------------------------------

ParametricDerivatives ParametricSurface::derivatives(const Vec2& uv) const {
  // Steps relative to the domain's size; the stencil may reach slightly outside the domain,
  // so position() must accept such points.
  return parametric_differences([this](const Vec2& q) { return position(q); }, uv,
                                domain().max - domain().min);
}

double Surface::point_quantity(const std::string&, const Vec3&) const {
  return std::numeric_limits<double>::quiet_NaN();
}

Vec2 ParametricSurface::unwrap_near(const Vec2& uv, const Vec2& reference) const {
  const ParameterDomain d = domain();
  Vec2 out = uv;
  const bool periodic[2] = {d.periodic_u, d.periodic_v};
  for (int a = 0; a < 2; ++a) {
    if (!periodic[a]) continue;
    const double period = d.max[a] - d.min[a];
    out[a] -= period * std::round((out[a] - reference[a]) / period);
  }
  return out;
}

Vec2 ParametricSurface::wrap_into_domain(const Vec2& uv) const {
  const ParameterDomain d = domain();
  Vec2 out = uv;
  const bool periodic[2] = {d.periodic_u, d.periodic_v};
  for (int a = 0; a < 2; ++a) {
    const double period = d.max[a] - d.min[a];
    if (periodic[a])
      out[a] = d.min[a] +
               period * (((out[a] - d.min[a]) / period) - std::floor((out[a] - d.min[a]) / period));
    else
      out[a] = std::clamp(out[a], d.min[a], d.max[a]);
  }
  return out;
}

Vec3 ParametricSurface::normal(const Vec2& uv) const {
  const ParametricDerivatives d = derivatives(uv);
  return d.su.cross(d.sv).normalized();
}

PrincipalCurvatures ParametricSurface::curvatures(const Vec2& uv) const {
  const ParametricDerivatives d = derivatives(uv);
  const Vec3 n = d.su.cross(d.sv).normalized();
  // Orthonormal frame e1 = Su/|Su|, e2 = n x e1; [Su Sv] = [e1 e2] R with R upper triangular.
  const Vec3 e1 = d.su.normalized();
  const Vec3 e2 = n.cross(e1);
  Mat2 R;
  R << d.su.norm(), d.sv.dot(e1), 0.0, d.sv.dot(e2);
  // Second fundamental form; the shape operator in the frame is R^-T II R^-1, negated so that
  // a sphere with outward normal (where <Suu, n> < 0) has positive curvature.
  Mat2 II;
  II << d.suu.dot(n), d.suv.dot(n), d.suv.dot(n), d.svv.dot(n);
  const Mat2 Rinv = R.inverse();
  const Mat2 shape = -(Rinv.transpose() * II * Rinv);
  return principal_curvatures_in_frame(shape, e1, e2, n);
}

// ---- ImplicitSurface ------------------------------------------------------------------------

double ImplicitSurface::value_gradient(const Vec3& p, Vec3& gradient) const {
  return gradient_differences([this](const Vec3& q) { return value(q); }, p, difference_step(),
                              gradient);
}

Mat3 ImplicitSurface::hessian(const Vec3& p) const {
  // Differences of gradients with a step ten times the gradient's: when value_gradient() is
  // itself a difference quotient its rounding error is then divided by a larger step.
  const double h = 10.0 * difference_step();
  Mat3 H;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = h * Vec3::Unit(i);
    Vec3 gp, gm;
    value_gradient(p + e, gp);
    value_gradient(p - e, gm);
    H.col(i) = (gp - gm) / (2.0 * h);
  }
  return 0.5 * (H + H.transpose());
}

double ImplicitSurface::value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& H) const {
  H = hessian(p);
  return value_gradient(p, gradient);
}

PrincipalCurvatures ImplicitSurface::curvatures(const Vec3& p) const {
  // Goldman 2005, "Curvature formulas for implicit curves and surfaces": the shape operator is
  // the Hessian restricted to the tangent plane and divided by |grad F| (the level set's
  // curvature; F < 0 inside, so a sphere gets +1/R). In an orthonormal tangent frame this is a
  // symmetric 2x2 matrix whose eigen-pairs are the principal curvatures and directions; its
  // determinant and half trace are Goldman's Gaussian and mean curvatures (up to his sign).
  Vec3 g;
  Mat3 H;
  value_gradient_hessian(p, g, H);
  const double gnorm = g.norm();
  if (!(gnorm > 0.0)) return PrincipalCurvatures{};
  const Vec3 n = g / gnorm;
  const Vec3 e1 = n.unitOrthogonal();
  const Vec3 e2 = n.cross(e1);
  Mat2 shape;
  shape << e1.dot(H * e1), e1.dot(H * e2), e2.dot(H * e1), e2.dot(H * e2);
  return principal_curvatures_in_frame(shape / gnorm, e1, e2, n);
}

}  // namespace dynamesh
