// Mesh quality measures (core/geometry/mesh_quality) against closed forms, and the adapter's
// temporal-coherence figures (StepStats) against cases whose answer is known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/mesh/base_meshes.h"
#include "test_smoothing_support.h"

namespace dynamesh {
namespace {

// A 4-8 grid of the unit square is made of right isosceles triangles: R / (2 r) is
// (sqrt 2 + 1) / 2 = 1.2071 for every one, so every percentile and the maximum are that.
TEST(Quality, AspectDistributionOfRightIsoscelesGrid) {
  const Mesh48 mesh = make_grid_mesh(4, 4, Vec2(0, 0), Vec2(1, 1));
  const double expected = (std::sqrt(2.0) + 1) / 2;
  const AspectDistribution d = aspect_distribution(mesh);
  EXPECT_EQ(d.triangles, mesh.n_faces());
  EXPECT_NEAR(d.p50, expected, 1e-12);
  EXPECT_NEAR(d.p99, expected, 1e-12);
  EXPECT_NEAR(d.max, expected, 1e-12);
  EXPECT_EQ(d.histogram[1], mesh.n_faces());  // the bin [1.1, 1.25)
  const auto range = angle_range_deg(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR(range[0], 45.0, 1e-12);
  EXPECT_NEAR(range[1], 90.0, 1e-12);
}

// Percentiles are nearest-rank: stretching one face of 100 moves the max, not the p99 (the
// 99th of 100 sorted values) nor the median.
TEST(Quality, AspectPercentilesAreNearestRank) {
  Mesh48 mesh = make_grid_mesh(10, 5, Vec2(0, 0), Vec2(2, 1));  // 50 squares of 2 triangles
  ASSERT_EQ(mesh.n_faces(), 100u);
  std::vector<Face> faces;
  Vertex lonely;  // a square's corner that no diagonal reaches: one incident face
  for (Vertex v : mesh.live_vertices()) {
    mesh.incident_faces(v, faces);
    if (faces.size() == 1) lonely = v;
  }
  ASSERT_TRUE(lonely.is_valid());
  // Halfway towards the opposite edge's midpoint: the right angle opens to 127 degrees.
  mesh.incident_faces(lonely, faces);
  const auto v = mesh.vertices(faces[0]);
  Vec3 mid = -mesh.position(lonely);
  for (Vertex w : v) mid += 0.5 * mesh.position(w);
  mesh.position(lonely) = 0.5 * (mesh.position(lonely) + mid);
  const AspectDistribution d = aspect_distribution(mesh);
  const double right = (std::sqrt(2.0) + 1) / 2;
  EXPECT_GT(d.max, right + 0.01);
  EXPECT_NEAR(d.p99, right, 1e-12);
  EXPECT_NEAR(d.p50, right, 1e-12);
}

// Edges of an n x n grid of the unit square: 2 n (n + 1) axis edges of length 1/n and n^2
// diagonals of length sqrt 2 / n. A half-plane selects edges by their midpoints.
TEST(Quality, EdgeLengthSpreadClosedForm) {
  const int n = 4;
  const Mesh48 mesh = make_grid_mesh(n, n, Vec2(0, 0), Vec2(1, 1));
  const EdgeLengthSpread all = edge_length_spread(mesh);
  const double axis = 2.0 * n * (n + 1), diag = n * n, h = 1.0 / n;
  EXPECT_EQ(all.edges, static_cast<std::size_t>(axis + diag));
  EXPECT_NEAR(all.min, h, 1e-12);
  EXPECT_NEAR(all.max, std::sqrt(2.0) * h, 1e-12);
  EXPECT_NEAR(all.ratio(), std::sqrt(2.0), 1e-12);
  const double mean = (axis * h + diag * std::sqrt(2.0) * h) / (axis + diag);
  EXPECT_NEAR(all.mean, mean, 1e-12);
  const double second = (axis * h * h + diag * 2 * h * h) / (axis + diag);
  EXPECT_NEAR(all.stddev, std::sqrt(second - mean * mean), 1e-12);
  // Only the n vertical edges on x = 0 have their midpoint at x < h / 2.
  const EdgeLengthSpread left =
      edge_length_spread(mesh, [&](const Vec3& p) { return p.x() < h / 2; });
  EXPECT_EQ(left.edges, static_cast<std::size_t>(n));
  EXPECT_NEAR(left.cv(), 0.0, 1e-12);
}

// A static surface: every vertex survives and none moves.
TEST(Quality, TemporalCoherenceOnStaticSurface) {
  test::SceneRun run = test::start_scene("twist", AdaptOptions{}, 0.4);
  for (int i = 0; i < 3; ++i) {
    const StepStats& s = run.adapter->step(0.4);
    EXPECT_EQ(s.kept_fraction, 1.0);
    EXPECT_EQ(s.survivor_displacement_max, 0.0);
  }
}

// The sphere without smoothing: normal correction moves each surviving vertex radially from
// R(t_{i-1}) to R(t_i), so every survivor moves exactly R(t_i) - R(t_{i-1}) (to rounding).
TEST(Quality, SurvivorDisplacementOnGrowingSphere) {
  AdaptOptions o;
  o.smoothing.enabled = false;
  test::SceneRun run = test::start_scene("sphere", o);
  auto radius = [](double t) { return 0.6 * std::pow(9.0 / 0.6, t); };
  for (int i = 1; i <= 5; ++i) {
    const double t0 = 0.02 * (i - 1), t1 = 0.02 * i;
    const StepStats& s = run.adapter->step(t1);
    const double expected = radius(t1) - radius(t0);
    EXPECT_NEAR(s.survivor_displacement_mean, expected, 1e-9 * expected) << "step " << i;
    EXPECT_NEAR(s.survivor_displacement_max, expected, 1e-9 * expected) << "step " << i;
    EXPECT_GT(s.kept_fraction, 0.5);
    EXPECT_LE(s.kept_fraction, 1.0);
    EXPECT_EQ(s.kept_fraction, static_cast<double>(s.vertices_kept) /
                                   static_cast<double>(s.vertices - s.splits + s.welds));
  }
}

// angles_within decides from cosines where it can: it must give angle_range_deg's verdict on
// every triangle, including those with an angle within rounding of a limit (built at 10 and 160
// degrees, and a hair either side) and degenerate ones.
TEST(Quality, AnglesWithinGivesAngleRangesVerdict) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto verdict = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    const auto r = angle_range_deg(a, b, c);
    return !(r[0] < 10.0 || r[1] > 160.0);
  };
  int near_limit = 0, inside = 0, outside = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    if (trial % 4 == 1) {
      // An angle at a of 10 or 160 degrees, give or take a few ulps of the angle.
      const double limit = (trial % 8 == 1 ? 10.0 : 160.0) * M_PI / 180.0;
      const double angle = limit * (1.0 + (trial % 5 - 2) * 1e-15);
      const Vec3 x = (b - a).normalized(), z = x.cross(c - a).normalized(), y = z.cross(x);
      c = a + (0.3 + 0.7 * std::abs(u(rng))) * (std::cos(angle) * x + std::sin(angle) * y);
      ++near_limit;
    } else if (trial % 4 == 2) {
      c = trial % 8 == 2 ? a : a + 0.5 * (b - a);  // degenerate: a repeated corner, collinear
    }
    const bool expected = verdict(a, b, c);
    (expected ? inside : outside) += 1;
    EXPECT_EQ(angles_within(a, b, c, 10.0, 160.0), expected) << trial;
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  EXPECT_EQ(near_limit, 5000);
}

}  // namespace
}  // namespace dynamesh
