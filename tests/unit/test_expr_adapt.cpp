// Typed surfaces under adaptation (issue 8): formulas equal to the built-in sphere and sinc
// adapt like them, within the error bound measured independently; a torus from a base-mesh
// file and periodic parametric surfaces adapt to closed manifolds of the right topology; a
// formula that breaks mid-run leaves the last good mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "mesh_measure.h"

namespace dynamesh {
namespace {

// What sparse sampling can miss (as test_adapter.cpp states it): the adapter's error comes
// from a stratified pattern of samples whose cells are much smaller than the triangles at
// D = 2000; the unseen excess between samples is a few per cent. 10% is the stated slack.
constexpr double kSparseSamplingSlack = 1.10;

AdaptOptions options() {
  AdaptOptions o;
  o.threshold = 0.008;
  o.epsilon = 0.002;
  return o;
}

struct SceneRun {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
};

// Geometric error everywhere (the criteria of every scene but the multi-criteria sphere), so
// that built-in and typed scenes are adapted alike.
SceneRun start(std::unique_ptr<Surface> surface, double t0) {
  SceneRun run;
  run.surface = std::move(surface);
  run.surface->set_time(t0);
  run.adapter = std::make_unique<Adapter>(*run.surface, options(),
                                          default_criteria("expr", 0.0, options(), 0.0));
  run.adapter->initialize();
  return run;
}

void advance(SceneRun& run, double t1, int steps) {
  const double t0 = run.surface->time();
  for (int i = 1; i <= steps; ++i) {
    run.adapter->step(t0 + (t1 - t0) * i / steps);
    const CheckReport report = run.adapter->mesh().check();
    ASSERT_TRUE(report.ok()) << "step " << i << ": " << report.summary();
  }
}

void expect_within_bound(const SceneRun& run, const std::string& what) {
  const AdaptOptions o = options();
  const auto dense = test::dense_error(run.adapter->mesh(), *run.surface, 20 * o.density, 7);
  EXPECT_LE(dense.max_error, (o.threshold + o.epsilon) * kSparseSamplingSlack)
      << what << ": dense error " << dense.max_error << " at (" << dense.worst.transpose() << "), "
      << run.adapter->mesh().n_faces() << " triangles";
  EXPECT_FALSE(run.adapter->stats().budget_hit) << what;
}

// Typed and built-in adaptations see the same surface through different derivatives (finite
// differences vs closed forms) and projections, so samples land slightly differently and a
// few diamonds near the threshold go the other way: fresh adaptations (initialize() at the
// same time) agree within 5%.
constexpr double kCountTolerance = 0.05;
// After animation steps the two meshes have histories: a diamond is kept anywhere inside the
// hysteresis band [T - eps, T + eps], so two correct meshes may differ by more. (On the
// sphere, whose curvature is the same everywhere, Equation-1 smoothing normalises curvature
// to [0, 1] over the mesh and so magnifies finite-difference noise of 1e-6 into different
// tangential moves.) Within 10%.
constexpr double kAnimatedCountTolerance = 0.10;

void expect_similar_counts(const SceneRun& typed, const SceneRun& builtin, const std::string& what,
                           double tolerance = kCountTolerance) {
  const double a = static_cast<double>(typed.adapter->mesh().n_faces());
  const double b = static_cast<double>(builtin.adapter->mesh().n_faces());
  EXPECT_LE(std::abs(a - b), tolerance * b) << what << ": typed " << a << " vs built-in " << b;
  ::testing::Test::RecordProperty(what + "_typed_over_builtin", std::to_string(a / b));
}

TEST(ExprAdapt, TypedSphereAdaptsLikeBuiltInSphere) {
  // sphere: R(t) = 0.6 (9/0.6)^t; the bounds hold it up to t = 0.44 (R = 2).
  SceneRun builtin = start(make_scene("sphere"), 0.0);
  const TextOptions typed_sphere{{"implicit", "sqrt(x^2+y^2+z^2) - 0.6*(9/0.6)^t"},
                                 {"bounds", "-2.2,-2.2,-2.2,2.2,2.2,2.2"}};
  SceneRun typed = start(make_scene("expr", {}, typed_sphere), 0.0);
  expect_similar_counts(typed, builtin, "sphere_t0");
  expect_within_bound(typed, "typed sphere t=0");
  advance(builtin, 0.2, 4);
  advance(typed, 0.2, 4);
  expect_similar_counts(typed, builtin, "sphere_animated_t0.2", kAnimatedCountTolerance);
  expect_within_bound(typed, "typed sphere t=0.2");
  const SceneRun fresh_builtin = start(make_scene("sphere"), 0.2);
  const SceneRun fresh_typed = start(make_scene("expr", {}, typed_sphere), 0.2);
  expect_similar_counts(fresh_typed, fresh_builtin, "sphere_t0.2");
}

TEST(ExprAdapt, TypedSincAdaptsLikeBuiltInSinc) {
  const std::string sinc =
      "0.6*sin(2*pi*t)*(sqrt(x^2+z^2) < 1e-9 ? 1 : "
      "sin(4*pi*sqrt(x^2+z^2))/(4*pi*sqrt(x^2+z^2)))*exp(-0.5*sqrt(x^2+z^2))";
  SceneRun builtin = start(make_scene("sinc"), 0.25);
  SceneRun typed = start(make_scene("expr", {}, {{"height", sinc}}), 0.25);
  expect_similar_counts(typed, builtin, "sinc_t0.25");
  expect_within_bound(typed, "typed sinc t=0.25");
  advance(builtin, 0.4, 3);
  advance(typed, 0.4, 3);
  expect_similar_counts(typed, builtin, "sinc_animated_t0.4", kAnimatedCountTolerance);
  expect_within_bound(typed, "typed sinc t=0.4");
  const SceneRun fresh_builtin = start(make_scene("sinc"), 0.4);
  const SceneRun fresh_typed = start(make_scene("expr", {}, {{"height", sinc}}), 0.4);
  expect_similar_counts(fresh_typed, fresh_builtin, "sinc_t0.4");
}

TEST(ExprAdapt, TorusFromBaseMeshIsClosedGenusOne) {
  const std::string torus = std::string(DYNAMESH_SOURCE_DIR) + "/assets/examples/torus.obj";
  SceneRun run =
      start(make_scene("expr", {},
                       {{"implicit", "sqrt((sqrt(x^2+y^2)-1)^2+z^2) - 0.4 - 0.1*sin(2*pi*t)"},
                        {"bounds", "-1.8,-1.8,-0.8,1.8,1.8,0.8"},
                        {"base-mesh", torus}}),
            0.0);
  for (double t : {0.0, 0.25}) {
    if (t > 0) advance(run, t, 5);
    const test::Topology topo = test::topology(run.adapter->mesh());
    EXPECT_EQ(topo.euler(), 0) << "t=" << t;
    EXPECT_EQ(topo.boundary_edges, 0) << "t=" << t;
    expect_within_bound(run, "torus t=" + std::to_string(t));
  }
}

// Distance of the mesh to the cylinder hypot(x, z) = 1, in closed form at dense random
// points of every face (plus its vertices): independent of the adapter's (u, v).
double cylinder_error(const Mesh48& mesh) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double worst = 0.0;
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    for (int k = 0; k < 60; ++k) {
      double a = u01(rng), b = u01(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 p =
          (1 - a - b) * mesh.position(v[0]) + a * mesh.position(v[1]) + b * mesh.position(v[2]);
      worst = std::max(worst, std::abs(std::hypot(p.x(), p.z()) - 1.0));
    }
  }
  return worst;
}

TEST(ExprAdapt, PeriodicCylinderClosesAlongTheSeam) {
  SceneRun run = start(
      make_scene(
          "expr", {},
          {{"parametric", "cos(u); v; sin(u)"}, {"domain", "0,2*pi,-1,1"}, {"periodic", "u"}}),
      0.0);
  const Mesh48& mesh = run.adapter->mesh();
  const test::Topology topo = test::topology(mesh);
  EXPECT_EQ(topo.euler(), 0);  // an annulus
  // Boundary edges lie on the ends y = +-1 only: none along the seam (u = 0 = 2 pi).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& tri : test::triangle_list(mesh))
    for (int i = 0; i < 3; ++i)
      ++uses[{std::min(tri[i], tri[(i + 1) % 3]), std::max(tri[i], tri[(i + 1) % 3])}];
  long end_edges = 0;
  for (const auto& [e, n] : uses) {
    if (n != 1) continue;
    const Vec3 &a = mesh.position(Vertex(e.first)), &b = mesh.position(Vertex(e.second));
    EXPECT_NEAR(std::abs(a.y()), 1.0, 1e-12) << "boundary edge inside the cylinder";
    EXPECT_NEAR(std::abs(b.y()), 1.0, 1e-12) << "boundary edge inside the cylinder";
    ++end_edges;
  }
  EXPECT_EQ(end_edges, topo.boundary_edges);
  EXPECT_GT(end_edges, 0);
  // A face interpolated across the seam the wrong way would span the whole cylinder.
  const AdaptOptions o = options();
  EXPECT_LE(cylinder_error(mesh), (o.threshold + o.epsilon) * kSparseSamplingSlack);
  EXPECT_LE(run.adapter->stats().max_error, o.threshold + o.epsilon + 1e-12);
}

TEST(ExprAdapt, PeriodicTorusAdaptsClosed) {
  // Parametric torus R = 1, r = 0.35 + 0.1 t, periodic in u and v.
  SceneRun run = start(make_scene("expr", {},
                                  {{"parametric",
                                    "(1 + (0.35+0.1*t)*cos(v))*cos(u); (0.35+0.1*t)*sin(v); "
                                    "(1 + (0.35+0.1*t)*cos(v))*sin(u)"},
                                   {"domain", "0,2*pi,0,2*pi"},
                                   {"periodic", "uv"}}),
                       0.0);
  advance(run, 0.5, 3);
  const test::Topology topo = test::topology(run.adapter->mesh());
  EXPECT_EQ(topo.euler(), 0);
  EXPECT_EQ(topo.boundary_edges, 0);
  EXPECT_LE(run.adapter->stats().max_error, options().threshold + options().epsilon + 1e-12);
}

TEST(ExprAdapt, FormulaBreakingMidRunKeepsTheLastGoodMesh) {
  // Fine for t < 0.5, NaN beyond (sqrt of a negative number).
  SceneRun run = start(make_scene("expr", {},
                                  {{"implicit", "sqrt(x^2+y^2+z^2) - 0.5 - 0.1*sqrt(0.5 - t)"},
                                   {"bounds", "-1,-1,-1,1,1,1"}}),
                       0.0);
  advance(run, 0.25, 2);
  const std::size_t faces = run.adapter->mesh().n_faces();
  EXPECT_THROW(run.adapter->step(0.75), std::invalid_argument);
  EXPECT_EQ(run.adapter->mesh().n_faces(), faces);
  EXPECT_TRUE(run.adapter->mesh().check().ok());
  EXPECT_EQ(run.surface->time(), 0.25);
}

}  // namespace
}  // namespace dynamesh
