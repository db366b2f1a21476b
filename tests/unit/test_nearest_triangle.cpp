// NearestTriangleIndex answers what a plain search over every triangle answers (the first of
// the nearest, within the reach), and nearest_on_triangle is checked against a dense lattice
// of the triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/geometry/nearest_triangle.h"

namespace dynamesh {
namespace {

using Triangles = std::vector<std::array<Vec3, 3>>;

NearestTriangleIndex::Hit plain_search(const Triangles& triangles, const Vec3& p,
                                       double max_squared_distance) {
  NearestTriangleIndex::Hit best;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const auto& [a, b, c] = triangles[k];
    const double d = (nearest_on_triangle(p, a, b, c) - p).squaredNorm();
    if (d <= max_squared_distance && d < best.squared_distance) best = {k, d};
  }
  return best;
}

Vec3 uniform_point(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return {u(rng), u(rng), u(rng)};
}

// Small triangles in the unit cube, long thin ones across it, and exact copies of some
// (equally near: the lowest index must win).
Triangles mixed_triangles(std::mt19937& rng) {
  Triangles t;
  std::normal_distribution<double> jitter(0.0, 0.03);
  for (int k = 0; k < 400; ++k) {
    const Vec3 a = uniform_point(rng, 0.0, 1.0);
    t.push_back({a, a + Vec3(jitter(rng), jitter(rng), jitter(rng)),
                 a + Vec3(jitter(rng), jitter(rng), jitter(rng))});
  }
  for (int k = 0; k < 20; ++k) {
    const Vec3 a = uniform_point(rng, 0.0, 1.0), b = uniform_point(rng, 0.0, 1.0);
    t.push_back({a, b, b + Vec3(jitter(rng), jitter(rng), jitter(rng))});
  }
  for (int k = 0; k < 40; ++k) t.push_back(t[static_cast<std::size_t>(k * 7)]);
  return t;
}

TEST(NearestTriangleIndex, AnswersAsAPlainSearchDoes) {
  std::mt19937 rng(7);
  const Triangles triangles = mixed_triangles(rng);
  const NearestTriangleIndex index(triangles);
  const double inf = std::numeric_limits<double>::infinity();
  int ties = 0, outside_reach = 0;
  for (int q = 0; q < 4000; ++q) {
    // Inside the cube, around it, and far from it; on a copied triangle's corner (a tie).
    Vec3 p = q % 4 == 3 ? uniform_point(rng, -3.0, 4.0) : uniform_point(rng, -0.2, 1.2);
    if (q % 50 == 0) p = triangles[static_cast<std::size_t>((q / 50) % 40 * 7)][1];
    const double reach = q % 3 == 0 ? 0.02 : inf;
    const double max_sq = reach * reach;
    const auto want = plain_search(triangles, p, max_sq);
    const auto got = index.nearest(p, max_sq);
    ASSERT_EQ(got.triangle, want.triangle) << "query " << q << " at " << p.transpose();
    if (want.triangle == NearestTriangleIndex::kNone) {
      ++outside_reach;
      continue;
    }
    ASSERT_EQ(got.squared_distance, want.squared_distance) << "query " << q;
    ties += want.squared_distance == 0.0;
  }
  // The cases the test is there for did occur.
  EXPECT_GT(ties, 40);
  EXPECT_GT(outside_reach, 200);
}

TEST(NearestTriangleIndex, EmptyAndSingleTriangle) {
  const NearestTriangleIndex empty(Triangles{});
  EXPECT_EQ(empty.nearest(Vec3(1, 2, 3)).triangle, NearestTriangleIndex::kNone);
  // A degenerate box (one flat triangle) and queries far off it.
  const NearestTriangleIndex one(Triangles{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}});
  const auto hit = one.nearest(Vec3(0.25, 0.25, 5.0));
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_DOUBLE_EQ(hit.squared_distance, 25.0);
  EXPECT_EQ(one.nearest(Vec3(0.25, 0.25, 5.0), 24.0).triangle, NearestTriangleIndex::kNone);
  EXPECT_EQ(one.nearest(Vec3(-1e6, 3e6, 0.0)).triangle, 0u);
}

// Against a lattice of order 400 on the triangle: the point found is no farther than the
// nearest lattice point, and no nearer than that minus the lattice's spacing.
TEST(NearestTriangle, AgreesWithADenseLattice) {
  std::mt19937 rng(3);
  constexpr int kOrder = 400;
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 a = uniform_point(rng, -1, 1), b = uniform_point(rng, -1, 1),
               c = trial % 5 == 0 ? a + 0.001 * (b - a) : uniform_point(rng, -1, 1);
    const Vec3 p = uniform_point(rng, -2, 2);
    double lattice = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kOrder; ++i)
      for (int j = 0; i + j <= kOrder; ++j) {
        const double u = double(i) / kOrder, v = double(j) / kOrder;
        lattice = std::min(lattice, ((1 - u - v) * a + u * b + v * c - p).norm());
      }
    const double spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / kOrder;
    const double found = (nearest_on_triangle(p, a, b, c) - p).norm();
    EXPECT_LE(found, lattice + 1e-12) << "trial " << trial;
    EXPECT_GE(found, lattice - spacing) << "trial " << trial;
  }
}

}  // namespace
}  // namespace dynamesh
