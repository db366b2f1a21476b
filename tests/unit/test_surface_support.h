// Test-side tools for the surface tests: fourth-order finite differences computed from values
// only (never from the code's own derivatives) and seeded random sampling.
#pragma once

#include <functional>
#include <random>

#include "core/geometry/vector_types.h"

namespace dynamesh::testing {

// d f / d e at x by the five-point stencil (error O(h^4)).
template <class F>
auto fd4_directional(const F& f, const Vec3& x, const Vec3& e, double h) {
  return (-f(x + 2 * h * e) + 8.0 * f(x + h * e) - 8.0 * f(x - h * e) + f(x - 2 * h * e)) /
         (12.0 * h);
}

inline Vec3 fd4_gradient(const std::function<double(const Vec3&)>& f, const Vec3& x, double h) {
  Vec3 g;
  for (int i = 0; i < 3; ++i) g(i) = fd4_directional(f, x, Vec3::Unit(i), h);
  return g;
}

// Diagonal: five-point second difference; off-diagonal: the five-point first difference
// applied twice. Both O(h^4).
inline Mat3 fd4_hessian(const std::function<double(const Vec3&)>& f, const Vec3& x, double h) {
  Mat3 H;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = Vec3::Unit(i);
    H(i, i) = (-f(x + 2 * h * e) + 16.0 * f(x + h * e) - 30.0 * f(x) + 16.0 * f(x - h * e) -
               f(x - 2 * h * e)) /
              (12.0 * h * h);
    for (int j = 0; j < i; ++j) {
      const Vec3 ej = Vec3::Unit(j);
      auto dj = [&](const Vec3& y) { return fd4_directional(f, y, ej, h); };
      H(i, j) = H(j, i) = fd4_directional(dj, x, e, h);
    }
  }
  return H;
}

class Random {
 public:
  explicit Random(unsigned seed = 12345) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine_); }
  Vec3 in_box(const Vec3& lo, const Vec3& hi) {
    return {uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y()), uniform(lo.z(), hi.z())};
  }
  Vec3 unit_vector() {
    for (;;) {
      const Vec3 v = in_box(Vec3::Constant(-1), Vec3::Constant(1));
      if (v.norm() > 0.1 && v.norm() <= 1.0) return v.normalized();
    }
  }

 private:
  std::mt19937 engine_;
};

}  // namespace dynamesh::testing
