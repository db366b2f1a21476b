// The smoothing's move onto an implicit surface from a known evaluation (surface_move.h,
// second_order_landing; SmoothingOptions::evaluations): against the sphere's closed form, by
// the order at which the landing's residual falls with the move on a surface whose curvature
// varies (the twisted Lp bar), and through smooth_tangentially, where the vertices must land on
// the same surface points as from p + move, with the evaluations counted by a wrapper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "core/geometry/surface_move.h"
#include "core/geometry/tangential_smoothing.h"
#include "core/surface/projection.h"
#include "core/surface/scene_registry.h"
#include "scene_run.h"
#include "test_surface_support.h"
#include "tests/support/counting_surface.h"

namespace dynamesh {
namespace {

using testing::Random;
constexpr double kEps = std::numeric_limits<double>::epsilon();

PointEvaluation evaluated_at(const ImplicitSurface& s, const Vec3& p) {
  PointEvaluation e;
  e.point = p;
  e.value = s.value_gradient(p, e.gradient);
  e.epoch = 1;
  return e;
}

// A random direction on the tangent plane of unit normal n.
Vec3 tangent_direction(Random& rnd, const Vec3& n) {
  for (;;) {
    const Vec3 t = rnd.unit_vector();
    const Vec3 d = t - t.dot(n) * n;
    if (d.norm() > 0.1) return d.normalized();
  }
}

std::unique_ptr<ImplicitSurface> implicit_scene(const char* name, double t) {
  std::unique_ptr<Surface> s = make_scene(name);
  s->set_time(t);
  auto* implicit = dynamic_cast<ImplicitSurface*>(s.get());
  if (implicit == nullptr) return nullptr;
  s.release();
  return std::unique_ptr<ImplicitSurface>(implicit);
}

// F = |p| - R: a tangential move m from p lands at p + m - |m|^2 / (2R) n, whose distance to
// the sphere is sqrt((R - |m|^2 / (2R))^2 + |m|^2) - R = |m|^4 / (8 R^3) + O(|m|^6), where
// p + m is |m|^2 / (2R) away.
TEST(SecondOrderLanding, OnTheSphereTheResidualIsFourthOrder) {
  const std::unique_ptr<ImplicitSurface> sphere = implicit_scene("sphere", 0.0);
  ASSERT_TRUE(sphere);
  const double R = 0.6;  // SCENES.md: R0
  Random rnd(7);
  for (int i = 0; i < 50; ++i) {
    const Vec3 n = rnd.unit_vector();
    const Vec3 p = R * n;
    const PrincipalCurvatures k = sphere->curvatures(p);
    for (double length : {1e-3, 1e-2, 5e-2}) {
      const Vec3 move = length * tangent_direction(rnd, n);
      const Vec3 q = second_order_landing(evaluated_at(*sphere, p), k, move);
      const double m2 = move.squaredNorm(), lift = R - m2 / (2 * R);
      const double landed = std::sqrt(lift * lift + m2) - R;  // the closed form above
      // (to rounding: a few ulp of R, which |q| - R cancels)
      EXPECT_NEAR(sphere->value(q), landed, 1e-9 * landed + 8 * kEps * R) << "move " << length;
      EXPECT_LE(landed, 1.01 * m2 * m2 / (8 * R * R * R)) << "move " << length;
      EXPECT_NEAR(sphere->value(p + move), std::sqrt(R * R + m2) - R, 1e-15);
    }
  }
}

// On a surface whose curvature varies the landing's residual is third order in the move: the
// median residual over many points falls by about 8 when the move halves, against 4 for p + move.
TEST(SecondOrderLanding, OnTheTwistedBarTheResidualFallsAsTheMoveCubed) {
  const std::unique_ptr<ImplicitSurface> twist = implicit_scene("twist", 0.7);
  ASSERT_TRUE(twist);
  Random rnd(11);
  const double scale = twist->length_scale();
  struct Residuals {
    std::vector<double> straight, landed;
  };
  const double lengths[] = {4e-3 * scale, 2e-3 * scale, 1e-3 * scale};
  Residuals at[3];
  for (int i = 0; i < 400; ++i) {
    const ProjectionResult on =
        project_to_surface(*twist, rnd.in_box({-1.5, -0.5, -0.5}, {1.5, 0.5, 0.5}));
    if (!on.converged) continue;
    const PointEvaluation e = evaluated_at(*twist, on.point);
    const PrincipalCurvatures k = twist->curvatures(on.point);
    const Vec3 direction = tangent_direction(rnd, e.gradient.normalized());
    for (int j = 0; j < 3; ++j) {
      const Vec3 move = lengths[j] * direction;
      const Vec3 q = second_order_landing(e, k, move);
      Vec3 g;
      const double landed = std::abs(twist->value_gradient(q, g)) / g.norm();
      const double straight = std::abs(twist->value_gradient(on.point + move, g)) / g.norm();
      at[j].straight.push_back(straight);
      at[j].landed.push_back(landed);
    }
  }
  ASSERT_GT(at[0].landed.size(), 300u);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  for (int j = 0; j + 1 < 3; ++j) {
    const double straight_ratio = median(at[j].straight) / median(at[j + 1].straight);
    const double landed_ratio = median(at[j].landed) / median(at[j + 1].landed);
    EXPECT_NEAR(straight_ratio, 4.0, 0.4) << "move " << lengths[j];
    EXPECT_GT(landed_ratio, 6.5) << "move " << lengths[j];
    EXPECT_LT(median(at[j].landed), 0.05 * median(at[j].straight)) << "move " << lengths[j];
    std::printf(
        "move %.3g: median residual %.3g landed, %.3g straight; halving the move: / %.2f, "
        "/ %.2f\n",
        lengths[j], median(at[j].landed), median(at[j].straight), landed_ratio, straight_ratio);
  }
}

// Where the model does not hold (the correction it asks for is longer than the move itself) the
// start is p + move.
TEST(SecondOrderLanding, FallsBackToTheStraightMoveWhereTheModelFails) {
  const std::unique_ptr<ImplicitSurface> sphere = implicit_scene("sphere", 0.0);
  ASSERT_TRUE(sphere);
  const Vec3 p(0.6, 0.0, 0.0);
  const PrincipalCurvatures k = sphere->curvatures(p);
  const Vec3 long_move(0.0, 3.0, 0.0);  // |m| k / 2 = 2.5 > 1
  EXPECT_EQ(second_order_landing(evaluated_at(*sphere, p), k, long_move), p + long_move);
  PointEvaluation flat = evaluated_at(*sphere, p);
  flat.gradient = Vec3::Zero();
  const Vec3 move(0.0, 1e-3, 0.0);
  EXPECT_EQ(second_order_landing(flat, k, move), p + move);
}

struct SmoothedCopy {
  Mesh48 mesh;
  SmoothingResult result;
  std::size_t evaluations = 0;  // of F and grad F
};

SmoothedCopy smooth_copy(const Mesh48& mesh, CountingSurface& surface,
                         const std::vector<PointEvaluation>* known, std::uint64_t epoch) {
  SmoothedCopy out{mesh, {}, 0};
  SmoothingOptions o;
  o.evaluations = known;
  o.evaluations_epoch = epoch;
  surface.reset_counts();
  out.result = smooth_tangentially(out.mesh, surface, o);
  out.evaluations = surface.count(CountingSurface::kValueGradient);
  return out;
}

// A capsule-bend mesh carried to a later time: every vertex projected by the test, which keeps
// F and grad F where it landed. Smoothed from those, the vertices land on the surface within the
// projection's tolerance, at the points the moves from p + move reach (to a thousandth of an
// edge), with at most 0.7 of the evaluations (about one per move instead of a Newton step and
// two). Entries of another epoch are not used: the smoothing is then the plain one, bit for bit.
TEST(SmoothingFromKnownEvaluations, SameSurfacePointsWithFewerEvaluations) {
  AdaptOptions o;
  o.threshold = 1e-3;
  o.epsilon = 2.5e-4;
  test::SceneRun run = test::start_scene("capsule-bend", o, 0.5);
  run.adapter->step(0.52);
  CountingSurface surface(implicit_scene("capsule-bend", 0.53));
  Mesh48 mesh = run.adapter->mesh();
  mesh.clear_listeners();
  std::vector<PointEvaluation> known(mesh.vertex_capacity());
  double edges = 0.0;
  std::size_t edge_count = 0;
  for (Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(surface.wrapped(), mesh.position(v));
    ASSERT_TRUE(r.converged);
    mesh.position(v) = r.point;
    known[v.idx] = PointEvaluation{r.point, r.value, r.gradient, 1};
  }
  for (Face f : mesh.live_faces()) {
    const auto c = mesh.vertices(f);
    for (int e = 0; e < 3; ++e, ++edge_count)
      edges += (mesh.position(c[e]) - mesh.position(c[(e + 1) % 3])).norm();
  }
  const double mean_edge = edges / static_cast<double>(edge_count);

  const SmoothedCopy from_landing = smooth_copy(mesh, surface, &known, 1);
  const SmoothedCopy plain = smooth_copy(mesh, surface, nullptr, 0);
  const SmoothedCopy stale = smooth_copy(mesh, surface, &known, 2);
  ASSERT_GT(plain.result.moved, mesh.n_vertices() / 2);
  EXPECT_EQ(from_landing.result.projection_failures, 0u);
  EXPECT_NEAR(static_cast<double>(from_landing.result.moved),
              static_cast<double>(plain.result.moved), 1e-3 * plain.result.moved);
  const double tolerance = ProjectionOptions{}.tolerance * surface.length_scale();
  double apart = 0.0, off = 0.0;
  for (Vertex v : mesh.live_vertices()) {
    const Vec3& p = from_landing.mesh.position(v);
    Vec3 g;
    off = std::max(off, std::abs(surface.wrapped().value_gradient(p, g)) / g.norm());
    apart = std::max(apart, (p - plain.mesh.position(v)).norm());
    EXPECT_EQ(stale.mesh.position(v), plain.mesh.position(v));
  }
  EXPECT_LE(off, tolerance);
  EXPECT_LE(apart, 1e-3 * mean_edge);
  EXPECT_EQ(stale.evaluations, plain.evaluations);
  EXPECT_LE(static_cast<double>(from_landing.evaluations),
            0.7 * static_cast<double>(plain.evaluations));
  std::printf("evaluations: %zu from the landing points, %zu from p + move (%zu moves)\n",
              from_landing.evaluations, plain.evaluations, plain.result.moved);
}

}  // namespace
}  // namespace dynamesh
