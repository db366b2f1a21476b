// Shared helpers for the volume tests: oblique anisotropic grids, balls and ellipsoids
// rasterised on them, exact distances to an ellipsoid, Newton projection and the shape
// operator of a level set, all computed here independently of the code under test.
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh::test {

// A grid of `dims` voxels with spacing `spacing`, rotated by `angle` about `axis`, whose
// centre lands on `centre`.
inline VoxelGrid oblique_grid(const std::array<int, 3>& dims, const Vec3& spacing, double angle,
                              const Vec3& axis, const Vec3& centre) {
  VoxelGrid g;
  g.dims = dims;
  g.linear = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix() * spacing.asDiagonal();
  const Vec3 mid(0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1));
  g.offset = centre - g.linear * mid;
  return g;
}

// Fills a mask or volume from a predicate on the world position of each voxel centre.
template <class T>
VoxelVolume<T> rasterise(const VoxelGrid& grid, const std::function<bool(const Vec3&)>& inside,
                         T in, T out) {
  VoxelVolume<T> v(grid, out);
  for (int k = 0; k < grid.dims[2]; ++k)
    for (int j = 0; j < grid.dims[1]; ++j)
      for (int i = 0; i < grid.dims[0]; ++i)
        if (inside(grid.to_world(Vec3(i, j, k)))) v.at(i, j, k) = in;
  return v;
}

// Signed distance from q (in the ellipsoid's frame) to the ellipsoid with semi-axes e,
// negative inside. The closest point x = e_i^2 q_i / (t + e_i^2) solves
// sum (e_i q_i / (t + e_i^2))^2 = 1 for the root t > -min e^2 (Eberly, "Distance from a
// point to an ellipse, an ellipsoid, or a hyperellipsoid", 2013), found by bisection.
inline double ellipsoid_distance(const Vec3& q, const Vec3& e) {
  const auto g = [&](double t) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double r = e[i] * q[i] / (t + e[i] * e[i]);
      s += r * r;
    }
    return s - 1.0;
  };
  const double emin2 = e.minCoeff() * e.minCoeff();
  double lo = -emin2 + 1e-12, hi = e.maxCoeff() * q.norm() + 1.0;
  // g decreases in t; g(lo) may be finite if q lies on a plane of symmetry: clamp then.
  if (g(lo) < 0.0) lo = -emin2 * (1.0 - 1e-9);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = e[i] * e[i] * q[i] / (t + e[i] * e[i]);
  const double d = (q - x).norm();
  const Vec3 r = q.cwiseQuotient(e);
  return r.squaredNorm() < 1.0 ? -d : d;
}

// Newton steps along the gradient onto {f = 0}.
inline Vec3 project(const std::function<double(const Vec3&, Vec3&)>& f, Vec3 p,
                    int iterations = 30) {
  for (int it = 0; it < iterations; ++it) {
    Vec3 g;
    const double v = f(p, g);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-20) break;
    p -= (v / g2) * g;
    if (std::abs(v) < 1e-10) break;
  }
  return p;
}

// Principal curvatures (magnitudes, sorted) of the level set through p: eigenvalues of the
// shape operator P H P / |g| restricted to the tangent plane, P = I - n n^T.
inline Vec2 principal_curvatures(const Vec3& g, const Mat3& h) {
  const Vec3 n = g.normalized();
  const Mat3 proj = Mat3::Identity() - n * n.transpose();
  const Mat3 shape = proj * h * proj / g.norm();
  Eigen::SelfAdjointEigenSolver<Mat3> es(shape);
  Vec3 ev = es.eigenvalues();
  // Drop the eigenvalue of the normal direction (the one closest to zero with eigenvector n).
  int normal = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(es.eigenvectors().col(i).dot(n)) > std::abs(es.eigenvectors().col(normal).dot(n)))
      normal = i;
  Vec2 k;
  int c = 0;
  for (int i = 0; i < 3; ++i)
    if (i != normal) k[c++] = ev[i];
  if (k[0] > k[1]) std::swap(k[0], k[1]);
  return k;
}

}  // namespace dynamesh::test
