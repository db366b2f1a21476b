// Hand-made snapshots for the rendering tests: a UV sphere with chosen per-vertex fields, so
// the renderer is tested without the adapter.
#pragma once

#include <cmath>
#include <numbers>

#include "core/adapt/mesh_snapshot.h"

namespace dynamesh::test {

// Sphere of `radius` at `center`, `rings` x `segments` quads split into triangles
// (counter-clockwise seen from outside), with fields "error", "curvature", "valence",
// "level" and "intensity" all set to `value` at every vertex.
inline MeshSnapshot sphere_snapshot(double radius = 1.0, Vec3 center = Vec3::Zero(),
                                    float value = 0.0f, int rings = 24, int segments = 48) {
  MeshSnapshot s;
  const auto vertex = [&](int i, int j) {
    return static_cast<std::uint32_t>(i * (segments + 1) + j);
  };
  for (int i = 0; i <= rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                   -std::sin(theta) * std::sin(phi));
      const Vec3 p = center + radius * n;
      s.bounds.extend(p);
      for (int k = 0; k < 3; ++k) {
        s.positions.push_back(static_cast<float>(p[k]));
        s.normals.push_back(static_cast<float>(n[k]));
      }
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                          d = vertex(i, j + 1);
      s.triangles.insert(s.triangles.end(), {a, b, c, a, c, d});
    }
  }
  for (const char* name : {"error", "curvature", "valence", "level", "intensity"}) {
    s.fields.push_back({name, std::vector<float>(s.n_vertices(), value)});
  }
  return s;
}

}  // namespace dynamesh::test
