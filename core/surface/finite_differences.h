// Central finite differences for surfaces known only through evaluation: the defaults of
// ParametricSurface / ImplicitSurface and the typed-formula surfaces.
// Steps are relative to the extent of the bounds or parameter domain, near the optimum for
// double precision: eps^(1/3) ~ 1e-5 for first derivatives (truncation h^2 and rounding
// eps/h balance), eps^(1/4) ~ 1e-4 for second derivatives (h^2 against eps/h^2). The stencils
// take every sample in one go so that a caller evaluates its formula with one cache lookup.
#pragma once

#include "core/geometry/vector_types.h"
#include "core/surface/surface.h"

namespace dynamesh {

constexpr double kFirstDifferenceStep = 1e-5;
constexpr double kSecondDifferenceStep = 1e-4;

// S(u, v) -> value and first and second derivatives, with steps relative to `size` (the
// domain's extent). `position(uv)` may be called slightly outside the domain.
template <class Position>
ParametricDerivatives parametric_differences(const Position& position, const Vec2& uv,
                                             const Vec2& size) {
  const double hu = kFirstDifferenceStep * size.x(), hv = kFirstDifferenceStep * size.y();
  const double Hu = kSecondDifferenceStep * size.x(), Hv = kSecondDifferenceStep * size.y();
  const Vec2 du(hu, 0.0), dv(0.0, hv), Du(Hu, 0.0), Dv(0.0, Hv);
  ParametricDerivatives d;
  d.s = position(uv);
  d.su = (position(uv + du) - position(uv - du)) / (2.0 * hu);
  d.sv = (position(uv + dv) - position(uv - dv)) / (2.0 * hv);
  d.suu = (position(uv + Du) - 2.0 * d.s + position(uv - Du)) / (Hu * Hu);
  d.svv = (position(uv + Dv) - 2.0 * d.s + position(uv - Dv)) / (Hv * Hv);
  d.suv = (position(uv + Du + Dv) - position(uv + Du - Dv) - position(uv - Du + Dv) +
           position(uv - Du - Dv)) /
          (4.0 * Hu * Hv);
  return d;
}

// F(p) -> value and gradient; step h (absolute).
template <class Value>
double gradient_differences(const Value& value, const Vec3& p, double h, Vec3& gradient) {
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = h * Vec3::Unit(i);
    gradient(i) = (value(p + e) - value(p - e)) / (2.0 * h);
  }
  return value(p);
}

// F(p) -> Hessian from second differences of values (19 evaluations; differencing a
// difference-quotient gradient would take 42); step H (absolute).
template <class Value>
Mat3 hessian_differences(const Value& value, const Vec3& p, double H) {
  const double f = value(p);
  Mat3 hessian;
  for (int i = 0; i < 3; ++i) {
    const Vec3 ei = H * Vec3::Unit(i);
    hessian(i, i) = (value(p + ei) - 2.0 * f + value(p - ei)) / (H * H);
    for (int j = i + 1; j < 3; ++j) {
      const Vec3 ej = H * Vec3::Unit(j);
      hessian(i, j) = hessian(j, i) =
          (value(p + ei + ej) - value(p + ei - ej) - value(p - ei + ej) + value(p - ei - ej)) /
          (4.0 * H * H);
    }
  }
  return hessian;
}

}  // namespace dynamesh
