// Independent dense measurement of a mesh's distance to its surface, for tests: its own
// random generator and sampling (uniform over each triangle at a chosen density, plus every
// vertex and edge midpoint) and the full Newton distance of SCENES.md — nothing from the
// adapter's samples, queues or first-order shortcuts.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"
#include "core/surface/surface_distance.h"

namespace dynamesh::test {

struct DenseError {
  double max_error = 0.0;
  std::size_t points = 0;
  Vec3 worst{Vec3::Zero()};
};

inline double distance_at(const Surface& surface, const Vec3 p[3], const Vec2 uv[3], double b0,
                          double b1, double b2) {
  const Vec3 x = b0 * p[0] + b1 * p[1] + b2 * p[2];
  if (const auto* par = dynamic_cast<const ParametricSurface*>(&surface)) {
    // Continuous across a periodic seam.
    const Vec2 uv1 = par->unwrap_near(uv[1], uv[0]), uv2 = par->unwrap_near(uv[2], uv[0]);
    return distance_to_surface(*par, x, par->wrap_into_domain(b0 * uv[0] + b1 * uv1 + b2 * uv2));
  }
  return distance_to_surface(dynamic_cast<const ImplicitSurface&>(surface), x);
}

// Visits the dense measurement points of one triangle as fn(b0, b1, b2): `n` uniformly random
// points, then the vertices and edge midpoints.
template <class Rng, class Fn>
void for_each_dense_point(int n, Rng& rng, Fn&& fn) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    double a = u01(rng), b = u01(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    fn(1 - a - b, a, b);
  }
  for (int i = 0; i < 3; ++i) {
    double b[3] = {0, 0, 0};
    b[i] = 1;
    fn(b[0], b[1], b[2]);
    b[i] = b[(i + 1) % 3] = 0.5;
    fn(b[0], b[1], b[2]);
  }
}

// Largest distance over one triangle (vertex positions p, parameters uv).
template <class Rng>
double dense_triangle_error(const Surface& surface, const Vec3 p[3], const Vec2 uv[3], int n,
                            Rng& rng) {
  double worst = 0.0;
  for_each_dense_point(n, rng, [&](double b0, double b1, double b2) {
    worst = std::max(worst, distance_at(surface, p, uv, b0, b1, b2));
  });
  return worst;
}

// `density`: random points per unit area (at least 3 per face). `keep(face)` selects faces.
inline DenseError dense_error(
    const Mesh48& mesh, const Surface& surface, double density, std::uint64_t seed,
    const std::function<bool(Face)>& keep = [](Face) { return true; }) {
  DenseError result;
  std::mt19937_64 rng(seed);
  for (Face f : mesh.live_faces()) {
    if (!keep(f)) continue;
    const auto v = mesh.vertices(f);
    const Vec3 p[3] = {mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])};
    const Vec2 uv[3] = {mesh.uv(v[0]), mesh.uv(v[1]), mesh.uv(v[2])};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const auto n = static_cast<int>(std::max(3.0, std::ceil(density * area)));
    for_each_dense_point(n, rng, [&](double b0, double b1, double b2) {
      const double d = distance_at(surface, p, uv, b0, b1, b2);
      ++result.points;
      if (d > result.max_error) {
        result.max_error = d;
        result.worst = b0 * p[0] + b1 * p[1] + b2 * p[2];
      }
    });
  }
  return result;
}

// The same for a triangle list of an implicit surface (a frame the CLI exported, read back):
// `keep(k)` selects triangles by their index in the list.
inline DenseError dense_error(
    const std::vector<Vec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const ImplicitSurface& surface, double density, std::uint64_t seed,
    const std::function<bool(std::size_t)>& keep = [](std::size_t) { return true; }) {
  DenseError result;
  std::mt19937_64 rng(seed);
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    if (!keep(k)) continue;
    const Vec3 p[3] = {positions[triangles[k][0]], positions[triangles[k][1]],
                       positions[triangles[k][2]]};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const auto n = static_cast<int>(std::max(3.0, std::ceil(density * area)));
    for_each_dense_point(n, rng, [&](double b0, double b1, double b2) {
      const Vec3 x = b0 * p[0] + b1 * p[1] + b2 * p[2];
      const double d = distance_to_surface(surface, x);
      ++result.points;
      if (d > result.max_error) {
        result.max_error = d;
        result.worst = x;
      }
    });
  }
  return result;
}

}  // namespace dynamesh::test
