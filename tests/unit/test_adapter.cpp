// Adaptation engine tests (issue 4): the error bound under independent dense measurement,
// no over-refinement, O(1/T) scaling, no flicker, hysteresis round trips, the multi-criteria
// sphere, and the mesh invariants after every step.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/adapt/adapter.h"
#include "core/mesh/bisection_map.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "scene_run.h"

namespace dynamesh {
namespace {

using test::SceneRun;

SceneRun start(const std::string& scene, const AdaptOptions& options, double t0 = 0.0) {
  return test::start_scene(scene, options, t0);
}

// Steps from t0 to t1 in `steps` steps, checking the invariants after each.
void advance(SceneRun& run, double t0, double t1, int steps) {
  for (int i = 1; i <= steps; ++i) {
    run.adapter->step(t0 + (t1 - t0) * i / steps);
    const CheckReport report = run.adapter->mesh().check();
    ASSERT_TRUE(report.ok()) << "step " << i << ": " << report.summary();
  }
}

AdaptOptions options_with(double threshold) {
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  return o;
}

const char* kGeometricScenes[] = {"capsule-bend", "sinc", "twist"};

// What sparse sampling can miss: the adapter's L-infinity error comes from samples, and the
// error between samples on a triangle is a smooth bump whose peak a stratified pattern
// approaches within about half a cell; with D = 2000 and T = 0.008 the cells are much
// smaller than the triangles, so the unseen excess is a few per cent. 10% is the stated
// slack.
constexpr double kSparseSamplingSlack = 1.10;

TEST(Adapter, DenseMeasurementStaysWithinTolerance) {
  const AdaptOptions o = options_with(0.008);
  for (const char* scene : kGeometricScenes) {
    SceneRun run = start(scene, o);
    for (double t : {0.0, 0.5, 1.0}) {
      if (t > 0) advance(run, run.surface->time(), t, 10);
      const auto dense = test::dense_error(run.adapter->mesh(), *run.surface, 20 * o.density, 99);
      const double bound = (o.threshold + o.epsilon) * kSparseSamplingSlack;
      EXPECT_LE(dense.max_error, bound)
          << scene << " at t=" << t << ": dense error " << dense.max_error << " at ("
          << dense.worst.transpose() << ") vs T+eps " << o.threshold + o.epsilon << " ("
          << dense.points << " points, " << run.adapter->mesh().n_faces() << " triangles)";
      EXPECT_LE(run.adapter->stats().max_error, o.threshold + o.epsilon + 1e-12);
      RecordProperty(std::string(scene) + "_t" + std::to_string(t),
                     std::to_string(dense.max_error / (o.threshold + o.epsilon)));
    }
  }
}

// Measures, outside the adapter, the error every possible weld would leave: a dense
// measurement of the two parent triangles it would restore. None may be clearly below the
// weld bound T (criteria.h). "Clearly": by more than the accuracy of the adapter's error estimate,
// the same 10% the dense test above allows in the other direction (kSparseSamplingSlack); on the
// twist at t = 0.3 the estimate reads up to 7% high near the threshold.
TEST(Adapter, WeldPassRunsToCompletion) {
  const AdaptOptions o = options_with(0.008);
  std::mt19937_64 rng(5);
  for (const char* scene : kGeometricScenes) {
    SceneRun run = start(scene, o);
    advance(run, 0.0, 0.3, 10);
    const Mesh48& mesh = run.adapter->mesh();
    std::size_t weldable = 0, too_fine = 0;
    for (Vertex v : mesh.live_vertices()) {
      DiamondChange plan;
      if (!mesh.plan_weld(v, plan)) continue;
      ++weldable;
      double worst = 0;
      for (int h = 0; h < plan.count; ++h) {
        const auto& pv = plan.halves[h].parent_vertices;
        const Vec3 p[3] = {mesh.position(pv[0]), mesh.position(pv[1]), mesh.position(pv[2])};
        const Vec2 uv[3] = {mesh.uv(pv[0]), mesh.uv(pv[1]), mesh.uv(pv[2])};
        worst = std::max(worst, test::dense_triangle_error(*run.surface, p, uv, 400, rng));
      }
      too_fine += worst < o.threshold / kSparseSamplingSlack;
    }
    EXPECT_GT(weldable, 10u) << scene;
    EXPECT_EQ(too_fine, 0u) << scene << ": " << too_fine << " of " << weldable
                            << " weldable vertices could have been welded";
  }
}

// Error of a flat triangle over a smooth surface grows with its area, so the triangle count
// needed for a threshold T scales like 1/T: halving T should double it. A 4-8 refinement
// level halves the area but, where the surface curves in one direction only (the capsule's
// cylinder), reduces the error by 1 or 4 alternately, so one halving of T can land between
// levels: the geometric mean over three halvings must be in [1.6, 2.5], each one in
// [1.2, 3.3].
TEST(Adapter, HalvingThresholdRoughlyDoublesTriangles) {
  for (const char* scene : kGeometricScenes) {
    double previous = 0, product = 1;
    for (double T : {0.016, 0.008, 0.004, 0.002}) {
      SceneRun run = start(scene, options_with(T), 0.3);
      const auto n = static_cast<double>(run.adapter->mesh().n_faces());
      if (previous > 0) {
        EXPECT_GE(n / previous, 1.2) << scene << " T=" << T;
        EXPECT_LE(n / previous, 3.3) << scene << " T=" << T;
        product *= n / previous;
      }
      previous = n;
    }
    EXPECT_GE(std::cbrt(product), 1.6) << scene;
    EXPECT_LE(std::cbrt(product), 2.5) << scene;
  }
}

TEST(Adapter, StaticSurfaceDoesNotFlicker) {
  for (const char* scene : {"capsule-bend", "sinc", "twist", "sphere"}) {
    SceneRun run = start(scene, options_with(0.008), 0.3);
    std::size_t splits = 0, welds = 0;
    for (int i = 0; i < 50; ++i) {
      const StepStats& s = run.adapter->step(0.3);
      splits += s.splits;
      welds += s.welds;
    }
    EXPECT_EQ(splits, 0u) << scene;
    EXPECT_EQ(welds, 0u) << scene;
  }
}

// Hysteresis makes the mesh depend on its history: a region is stable at any 4-8 level whose
// error lies in the band and whose parent's does not fall below it, and one level changes a
// region's error by a factor of 2 to 4 while the band spans (T+eps)/T = 1.25. A mesh
// that has been through a sweep may therefore sit up to one level away from a freshly
// initialised one (triangle count within [0.5, 2]); it must not drift further, and repeated
// sweeps must settle rather than accumulate.
void expect_sweeps_settle(const char* scene) {
  SceneRun run = start(scene, options_with(0.008), 0.25);
  const auto start_count = static_cast<double>(run.adapter->mesh().n_faces());
  std::vector<double> returns;
  for (int sweep = 0; sweep < 4; ++sweep) {
    advance(run, 0.25, 1.0, 20);
    advance(run, 1.0, 0.25, 20);
    returns.push_back(static_cast<double>(run.adapter->mesh().n_faces()) / start_count);
    EXPECT_GE(returns.back(), 0.5) << scene << " sweep " << sweep;
    EXPECT_LE(returns.back(), 2.0) << scene << " sweep " << sweep;
  }
  ::testing::Test::RecordProperty(std::string(scene) + "_returns",
                                  std::to_string(returns[0]) + " " + std::to_string(returns[3]));
  EXPECT_NEAR(returns[3] / returns[2], 1.0, 0.06) << scene << ": repeated sweeps accumulate";
}

TEST(Adapter, BackAndForthSweepReturnsWithinOneLevel) {
  for (const char* scene : {"capsule-bend", "sinc"}) expect_sweeps_settle(scene);
}

// Issue 13: the twisted bar used to drift upwards over many 0.25 <-> 1 sweeps (0.95, 1.04,
// 1.02, 1.06, 1.07, 1.08 times its first count; levelling off near 1.15 after about seven):
// not sample noise (three seeds alike) nor the weld decisions (no weldable vertex left below
// T), but the tangential smoothing on the twisted sides, whose diagonal principal directions
// steer Equation 1's moves along the bar; the vertices came back displaced along x and the
// 4-8 hierarchy kept the refinement that placement needed. The twist moves its points only
// within their cross-section's plane, and smoothing now does too (ImplicitSurface::
// invariant_axis): 0.98, 0.96, 0.94, 0.98, 0.97, 0.96. Smoothing in the rest bar's
// coordinates instead (the vertices slide under the bar, so their rest points move) drifted
// further: 0.99, 0.96, 1.10, 1.14, 1.21, 1.26.
// The fourth-over-third check alone let main's drift through (1.06 / 1.02 there), so six
// sweeps, and none may end more than 5% above the first (before: 1.08 / 0.95 = 1.14).
TEST(Adapter, TwistRepeatedSweepsDoNotAccumulate) {
  SceneRun run = start("twist", options_with(0.008), 0.25);
  const auto start_count = static_cast<double>(run.adapter->mesh().n_faces());
  std::vector<double> returns;
  for (int sweep = 0; sweep < 6; ++sweep) {
    advance(run, 0.25, 1.0, 20);
    advance(run, 1.0, 0.25, 20);
    returns.push_back(static_cast<double>(run.adapter->mesh().n_faces()) / start_count);
    EXPECT_GE(returns.back(), 0.85) << "sweep " << sweep;
    EXPECT_LE(returns.back(), 1.2) << "sweep " << sweep;
  }
  std::string trail;
  for (double r : returns) trail.append(" ").append(std::to_string(r));
  ::testing::Test::RecordProperty("twist_returns", trail);
  EXPECT_NEAR(returns[3] / returns[2], 1.0, 0.06) << trail;
  for (std::size_t k = 1; k < returns.size(); ++k)
    EXPECT_LE(returns[k] / returns[0], 1.05)
        << "sweep " << k << ": repeated sweeps accumulate;" << trail;
}

// Surfaces with a rest map (capsule-bend) carry their vertices with the material:
// without tangential smoothing, a vertex that lives through a step keeps its rest-space
// point, where correction along the normal alone lets a rotating cap slide under it by about
// the distance the surface moved (the creep that made capsule-bend's mesh grow with every
// bend cycle).
TEST(Adapter, VerticesFollowTheMaterialOfMappedSurfaces) {
  for (const char* scene : {"capsule-bend"}) {
    AdaptOptions o = options_with(0.008);
    o.smoothing.enabled = false;
    SceneRun run = start(scene, o, 0.25);
    const auto& surface = static_cast<const ImplicitSurface&>(*run.surface);
    const Mesh48& mesh = run.adapter->mesh();
    double worst = 0.0, moved = 0.0;
    std::size_t followed = 0;
    for (int i = 1; i <= 10; ++i) {
      std::vector<Vec3> rest(mesh.vertex_capacity()), world(mesh.vertex_capacity());
      // Lineage: parents and level (an id reused by a split would have others).
      std::vector<std::pair<std::array<Vertex, 2>, int>> lineage(mesh.vertex_capacity());
      std::vector<char> alive(mesh.vertex_capacity(), 0);
      for (Vertex v : mesh.live_vertices()) {
        rest[v.idx] = surface.to_rest(mesh.position(v));
        world[v.idx] = mesh.position(v);
        lineage[v.idx] = {mesh.parents(v), mesh.level(v)};
        alive[v.idx] = 1;
      }
      run.adapter->step(0.25 + 0.075 * i);
      for (Vertex v : mesh.live_vertices()) {
        if (v.idx >= alive.size() || !alive[v.idx]) continue;
        if (lineage[v.idx] != std::make_pair(mesh.parents(v), mesh.level(v))) continue;
        worst = std::max(worst, (surface.to_rest(mesh.position(v)) - rest[v.idx]).norm());
        moved = std::max(moved, (mesh.position(v) - world[v.idx]).norm());
        ++followed;
      }
    }
    EXPECT_GT(followed, 1000u) << scene;
    EXPECT_GT(moved, 1e-2) << scene << ": the surface must really move";
    EXPECT_LT(worst, 1e-7) << scene;
  }
}

// Paper Section 4.3 / Figure 6: at small radius the edge-length half is coarser than the
// error half; at large radius the reverse.
TEST(Adapter, MultiCriteriaSphere) {
  const AdaptOptions o = options_with(0.008);
  SceneRun run = start("sphere", o, 0.0);
  const double L = test::scene_edge_length(*run.surface);
  auto count_halves = [&](std::size_t& left, std::size_t& right) {
    left = right = 0;
    const Mesh48& mesh = run.adapter->mesh();
    for (Face f : mesh.live_faces()) {
      double x = 0;
      for (Vertex v : mesh.vertices(f)) x += mesh.position(v).x();
      (x < 0 ? left : right) += 1;
    }
  };
  std::size_t left, right;
  count_halves(left, right);
  EXPECT_LT(right, left) << "R = 0.6: the edge-length half should be coarser";
  advance(run, 0.0, 1.0, 20);
  count_halves(left, right);
  EXPECT_LT(left, right) << "R = 9: the error half should be coarser";
  // Away from x = 0, refinement edges of the edge-length half lie in the stated band
  // [L 2^(-1/2), L 2^(1/4)] (criteria.h). A few may sit below it: the 4-8 structure welds a
  // vertex only with its whole diamond, so a weld that one criterion allows can be blocked by
  // a finer neighbour (measured: 3 of 28476 edges, the shortest 0.885 L 2^(-1/2)). None may
  // fall a whole half-level lower, below L 2^(-3/4) (the band's lower end before the weld
  // bound moved to L), and 99.9% must be inside.
  const EdgeLengthCriterion band(L);
  const double lower = band.weld_below() / std::sqrt(2.0);
  const Mesh48& mesh = run.adapter->mesh();
  std::size_t inside = 0, checked = 0;
  double shortest = std::numeric_limits<double>::infinity();
  for (Face f : mesh.live_faces()) {
    bool far_right = true;
    for (Vertex v : mesh.vertices(f)) far_right = far_right && mesh.position(v).x() > 4 * L;
    if (!far_right) continue;
    const double len = (mesh.position(mesh.vertex(f, 1)) - mesh.position(mesh.vertex(f, 2))).norm();
    ++checked;
    shortest = std::min(shortest, len);
    EXPECT_LE(len, band.split_above() * (1 + 1e-9));
    inside += len >= lower * (1 - 1e-9);
  }
  ASSERT_GT(checked, 100u);
  EXPECT_GE(shortest, L * std::pow(2.0, -0.75));
  EXPECT_GE(static_cast<double>(inside), 0.999 * static_cast<double>(checked))
      << "refinement edges below " << lower << ", shortest " << shortest;
}

TEST(Adapter, EveryStepKeepsInvariantsAndReports) {
  for (const char* scene : {"capsule-bend", "sinc", "twist", "sphere"}) {
    SceneRun run = start(scene, options_with(0.01), 0.0);
    advance(run, 0.0, 1.0, 12);
    const StepStats& s = run.adapter->stats();
    EXPECT_EQ(s.triangles, run.adapter->mesh().n_faces());
    EXPECT_GT(s.vertices_kept, 0u);
    EXPECT_LE(s.vertices_kept, s.vertices);
    EXPECT_GT(s.samples, s.triangles - 1);  // at least one per triangle
    EXPECT_EQ(s.projection_failures, 0u) << scene;
  }
}

TEST(Adapter, TriangleBudgetStopsRefinementAndIsReported) {
  AdaptOptions o = options_with(0.001);
  o.max_triangles = 3000;
  SceneRun run = start("capsule-bend", o, 0.5);
  EXPECT_TRUE(run.adapter->stats().budget_hit);
  EXPECT_LE(run.adapter->mesh().n_faces(), 3000u);
  EXPECT_TRUE(run.adapter->mesh().check().ok());
}

}  // namespace
}  // namespace dynamesh
