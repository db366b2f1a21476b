#include "core/surface/volume/bspline_field.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {
namespace {

// Uniform cubic B-spline weights of the 4 taps floor(u)-1 .. floor(u)+2 at fraction t, and
// their first and second derivatives in t.
struct Weights {
  double w[3][4];  // [derivative order][tap]
};

template <int Order>
void bspline_weights(double t, Weights& out) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  out.w[0][0] = s * s * s / 6.0;
  out.w[0][1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  out.w[0][2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  out.w[0][3] = t3 / 6.0;
  if constexpr (Order >= 1) {
    out.w[1][0] = -0.5 * s * s;
    out.w[1][1] = 1.5 * t2 - 2.0 * t;
    out.w[1][2] = -1.5 * t2 + t + 0.5;
    out.w[1][3] = 0.5 * t2;
  }
  if constexpr (Order >= 2) {
    out.w[2][0] = s;
    out.w[2][1] = 3.0 * t - 2.0;
    out.w[2][2] = 1.0 - 3.0 * t;
    out.w[2][3] = t;
  }
}

}  // namespace

CubicBSplineField::CubicBSplineField(ScalarVolume coefficients)
    : coefficients_(std::move(coefficients)),
      to_voxel_(coefficients_.grid.linear.inverse()),
      upper_(Vec3(coefficients_.grid.dims[0] - 1, coefficients_.grid.dims[1] - 1,
                  coefficients_.grid.dims[2] - 1)) {}

double CubicBSplineField::value(const Vec3& p) const {
  return evaluate<0>(p, nullptr, nullptr);
}

double CubicBSplineField::value_gradient(const Vec3& p, Vec3& gradient) const {
  return evaluate<1>(p, &gradient, nullptr);
}

double CubicBSplineField::value_gradient_hessian(const Vec3& p, Vec3& gradient,
                                                 Mat3& hessian) const {
  return evaluate<2>(p, &gradient, &hessian);
}

template <int Order>
double CubicBSplineField::evaluate(const Vec3& p, Vec3* gradient, Mat3* hessian) const {
  const Vec3 u = to_voxel_ * (p - coefficients_.grid.offset);
  const Vec3 q = u.cwiseMax(Vec3::Zero()).cwiseMin(upper_);
  Vec3 gu;
  Mat3 hu;
  double f = evaluate_voxel<Order>(q, &gu, &hu);
  const bool outside = q != u;
  if constexpr (Order >= 1) {
    // Along clamped axes the field does not vary with u (the distance term takes over).
    for (int i = 0; i < 3; ++i)
      if (q[i] != u[i]) gu[i] = 0.0;
    *gradient = to_voxel_.transpose() * gu;
  }
  if constexpr (Order >= 2) *hessian = to_voxel_.transpose() * hu * to_voxel_;
  if (outside) {
    const Vec3 away = coefficients_.grid.linear * (u - q);
    const double distance = away.norm();
    f += distance;
    if constexpr (Order >= 1) *gradient += away / distance;
    if constexpr (Order >= 2) hessian->setZero();
  }
  return f;
}

template <int Order>
double CubicBSplineField::evaluate_voxel(const Vec3& u, Vec3* gradient_u, Mat3* hessian_u) const {
  const auto& dims = coefficients_.grid.dims;
  int base[3];
  Weights w[3];
  for (int a = 0; a < 3; ++a) {
    const double fl = std::floor(u[a]);
    base[a] = static_cast<int>(fl) - 1;
    bspline_weights<Order>(u[a] - fl, w[a]);
  }
  // Tap indices, clamped at the border (replicated edge coefficients).
  int ix[4], iy[4], iz[4];
  for (int t = 0; t < 4; ++t) {
    ix[t] = std::clamp(base[0] + t, 0, dims[0] - 1);
    iy[t] = std::clamp(base[1] + t, 0, dims[1] - 1);
    iz[t] = std::clamp(base[2] + t, 0, dims[2] - 1);
  }
  const float* c = coefficients_.values.data();
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  // Sums over x first (value, d/dx, d2/dx2 of each row), then y, then z.
  double f = 0, fx = 0, fy = 0, fz = 0, fxx = 0, fyy = 0, fzz = 0, fxy = 0, fxz = 0, fyz = 0;
  for (int kz = 0; kz < 4; ++kz) {
    double sy[3][3] = {};  // [x order][y order]
    for (int ky = 0; ky < 4; ++ky) {
      const float* row = c + iz[kz] * nxy + iy[ky] * nx;
      double sx[3] = {};
      for (int kx = 0; kx < 4; ++kx) {
        const double v = row[ix[kx]];
        sx[0] += w[0].w[0][kx] * v;
        if constexpr (Order >= 1) sx[1] += w[0].w[1][kx] * v;
        if constexpr (Order >= 2) sx[2] += w[0].w[2][kx] * v;
      }
      for (int ox = 0; ox <= Order; ++ox)
        for (int oy = 0; oy + ox <= Order; ++oy) sy[ox][oy] += w[1].w[oy][ky] * sx[ox];
    }
    const double wz0 = w[2].w[0][kz];
    f += wz0 * sy[0][0];
    if constexpr (Order >= 1) {
      const double wz1 = w[2].w[1][kz];
      fx += wz0 * sy[1][0];
      fy += wz0 * sy[0][1];
      fz += wz1 * sy[0][0];
      if constexpr (Order >= 2) {
        const double wz2 = w[2].w[2][kz];
        fxx += wz0 * sy[2][0];
        fyy += wz0 * sy[0][2];
        fzz += wz2 * sy[0][0];
        fxy += wz0 * sy[1][1];
        fxz += wz1 * sy[1][0];
        fyz += wz1 * sy[0][1];
      }
    }
  }
  if constexpr (Order >= 1) *gradient_u = Vec3(fx, fy, fz);
  if constexpr (Order >= 2) {
    *hessian_u << fxx, fxy, fxz,  //
        fxy, fyy, fyz,            //
        fxz, fyz, fzz;
  }
  return f;
}

}  // namespace dynamesh
