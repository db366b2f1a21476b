// Predictive sampling (issue 17, core/adapt/error_predictor.h): every frame of a smooth
// animation stays within the same bound as with full sampling under independent dense
// measurement; every skipped face's stale error plus its bound covers its true error; a
// sudden jump in time falls back to measuring; full sampling, the reference, is kept; and the
// two make the same decisions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/adapt/error_model.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "scene_run.h"
#include "tests/support/error_only_adapter.h"

namespace dynamesh {
namespace {

// The same slack the other accuracy tests state (test_adapter.cpp, kSparseSamplingSlack):
// what stochastic sampling can miss between its samples.
constexpr double kSlack = 1.10;
// Random points per face of the dense measurement, besides its vertices and edge midpoints.
constexpr int kDensePoints = 6;

AdaptOptions options_with(double threshold, Sampling sampling) {
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  o.sampling = sampling;
  return o;
}

// Independent dense error of every live face (dense_error.h's measurement: random points,
// vertices and edge midpoints, full Newton distance), `points` random points per face, in
// parallel with a generator per face.
std::vector<double> dense_face_errors(const Mesh48& mesh, const Surface& surface, int points) {
  std::vector<double> error(mesh.face_capacity(), 0.0);
  const std::vector<Face> faces = mesh.live_faces();
  const auto n = static_cast<std::int64_t>(faces.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f = faces[static_cast<std::size_t>(i)];
    const auto v = mesh.vertices(f);
    const Vec3 p[3] = {mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])};
    const Vec2 uv[3] = {mesh.uv(v[0]), mesh.uv(v[1]), mesh.uv(v[2])};
    std::mt19937_64 rng(977 * f.idx + 13);
    error[f.idx] = test::dense_triangle_error(surface, p, uv, points, rng);
  }
  return error;
}

// How much of its bound each face sampling skipped this step used: max over those faces of
// |error now - last measured error| / bound, where "error now" is what full sampling would
// have measured this step (the same samples, evaluated afresh on a copy of the store). Above
// 1 where a skipped face's error escaped its bound. `range`: the same against the face's
// reading range (ErrorPredictor::reading_range: the part of it on the side the error moved),
// above 1 where the error left it; `narrower`: skipped faces whose range is narrower than
// last error +- bound on some side (the range is not the bound again).
struct Usage {
  double bound = 0.0, range = 0.0;
  std::size_t narrower = 0;
};
Usage skipped_usage(const test::SceneRun& run) {
  const Mesh48& mesh = run.adapter->mesh();
  const SampleStore& samples = run.adapter->samples();
  const ErrorPredictor& predictor = run.adapter->predictor();
  std::vector<Face> skipped;
  for (Face f : mesh.live_faces())
    if (predictor.bound(samples, f) > 0.0) skipped.push_back(f);
  SampleStore fresh = samples;
  fresh.evaluate_faces(mesh, SurfaceProbe(*run.surface), skipped);
  Usage usage;
  for (Face f : skipped) {
    // A face whose pattern fresh measuring densified is measured on other samples.
    if (fresh.count(f) != samples.count(f)) continue;
    const double now = fresh.face_error(f), then = samples.face_error(f);
    const double bound = predictor.bound(samples, f);
    usage.bound = std::max(usage.bound, std::abs(now - then) / bound);
    const ErrorPredictor::Range r = predictor.reading_range(samples, f);
    usage.narrower += r.hi < then + bound || r.lo > then - bound;
    // A range that does not hold the last reading itself counts as escaped.
    const bool holds = r.lo <= then && then <= r.hi;
    usage.range = std::max(usage.range, !holds        ? std::numeric_limits<double>::infinity()
                                        : now >= then ? (now - then) / (r.hi - then)
                                                      : (then - now) / (then - r.lo));
  }
  return usage;
}

struct FrameCheck {
  double worst_ratio = 0.0;        // max over frames of dense error / (T + eps)
  double bound_usage = 0.0;        // max over frames of skipped_usage().bound
  double range_usage = 0.0;        // and of its .range
  std::size_t narrower = 0;        // summed .narrower
  double measured_fraction = 0.0;  // faces measured by sampling / faces, over all steps
  std::vector<std::size_t> triangles;
};

// The scene with the geometric error everywhere (the sphere's default is multi-criteria: an
// edge length on its x >= 0 half, where the error is not bounded).
test::SceneRun start_with_error_criterion(const std::string& scene, const AdaptOptions& o) {
  test::SceneRun run;
  run.surface = make_scene(scene);
  run.surface->set_time(0.0);
  run.adapter = test::error_only_adapter(*run.surface, o);
  return run;
}

// 100 steps over [0, 1], judging every frame.
FrameCheck run_animation(const std::string& scene, Sampling sampling, double threshold) {
  const AdaptOptions o = options_with(threshold, sampling);
  test::SceneRun run = start_with_error_criterion(scene, o);
  FrameCheck check;
  double measured = 0, faces = 0;
  const double band = o.threshold + o.epsilon;
  for (int i = 1; i <= 100; ++i) {
    faces += static_cast<double>(run.adapter->mesh().n_faces());  // what sampling sees
    const StepStats& s = run.adapter->step(i / 100.0);
    measured += static_cast<double>(s.faces_measured);
    check.triangles.push_back(s.triangles);
    const Mesh48& mesh = run.adapter->mesh();
    const std::vector<double> dense = dense_face_errors(mesh, *run.surface, kDensePoints);
    for (Face f : mesh.live_faces())
      check.worst_ratio = std::max(check.worst_ratio, dense[f.idx] / band);
    const Usage usage = skipped_usage(run);
    check.bound_usage = std::max(check.bound_usage, usage.bound);
    check.range_usage = std::max(check.range_usage, usage.range);
    check.narrower += usage.narrower;
  }
  check.measured_fraction = measured / faces;
  return check;
}

class PredictiveAnimation : public ::testing::TestWithParam<const char*> {};

TEST_P(PredictiveAnimation, EveryFrameWithinToleranceAsWithFullSampling) {
  const std::string scene = GetParam();
  const double threshold = 0.002;
  const FrameCheck predictive = run_animation(scene, Sampling::kPredictive, threshold);
  const FrameCheck full = run_animation(scene, Sampling::kFull, threshold);
  EXPECT_LE(predictive.worst_ratio, kSlack) << scene;
  EXPECT_LE(full.worst_ratio, kSlack) << scene;
  // Every skipped face's error stayed within its bound of its last measurement.
  EXPECT_LE(predictive.bound_usage, 1.0) << scene;
  // And within its reading range, which decides the split (ErrorPredictor::select) and the
  // star's current error (Adapter::star_error_range); narrower than the bound on many faces.
  EXPECT_LE(predictive.range_usage, 1.0) << scene;
  EXPECT_GT(predictive.narrower, 0u) << scene;
  // Not vacuous: prediction did skip faces (at 100 steps over [0, 1] about half; many more
  // with smaller steps, bench_adapter.cpp), except on the sphere, whose radius grows by 2.7%
  // every step, so that every face's error does too. Full sampling measured every face.
  if (scene != "sphere") {
    EXPECT_LT(predictive.measured_fraction, 0.8) << scene;
  }
  EXPECT_EQ(full.measured_fraction, 1.0) << scene;
  // The same decisions give the same meshes; allow the rare face whose true error crossed a
  // band edge within its bound's slack to decide differently.
  for (std::size_t i = 0; i < full.triangles.size(); ++i)
    EXPECT_NEAR(static_cast<double>(predictive.triangles[i]),
                static_cast<double>(full.triangles[i]), 0.02 * full.triangles[i])
        << scene << " step " << i + 1;
  RecordProperty("measured_fraction", std::to_string(predictive.measured_fraction));
  RecordProperty("worst_ratio", std::to_string(predictive.worst_ratio));
  RecordProperty("bound_usage", std::to_string(predictive.bound_usage));
  RecordProperty("range_usage", std::to_string(predictive.range_usage));
  std::printf(
      "%s: measured %.3f of faces, dense/(T+eps) %.3f (full %.3f), bound usage %.3f, range usage "
      "%.3f (%zu narrower)\n",
      scene.c_str(), predictive.measured_fraction, predictive.worst_ratio, full.worst_ratio,
      predictive.bound_usage, predictive.range_usage, predictive.narrower);
}

INSTANTIATE_TEST_SUITE_P(Scenes, PredictiveAnimation,
                         ::testing::Values("twist", "capsule-bend", "sinc", "sphere"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// One big step: vertices move far against their triangles, so prediction must fall back
// to measuring: far more faces are measured than in a small step, every face's error stays
// within its last measurement plus its bound, the frame within the band, and the mesh is
// full sampling's.
TEST(PredictiveSampling, SuddenJumpInTimeFallsBackToMeasuring) {
  for (const char* scene : {"twist", "capsule-bend", "sinc"}) {
    test::SceneRun predictive =
        test::start_scene(scene, options_with(0.002, Sampling::kPredictive), 0.1);
    test::SceneRun full = test::start_scene(scene, options_with(0.002, Sampling::kFull), 0.1);
    double small_share = 0;
    for (double t : {0.101, 0.102, 0.103}) {  // small steps first: references exist
      const double faces = static_cast<double>(predictive.adapter->mesh().n_faces());
      small_share = static_cast<double>(predictive.adapter->step(t).faces_measured) / faces;
      full.adapter->step(t);
    }
    const double faces = static_cast<double>(predictive.adapter->mesh().n_faces());
    const StepStats p = predictive.adapter->step(0.9);
    const StepStats f = full.adapter->step(0.9);
    EXPECT_GT(static_cast<double>(p.faces_measured) / faces, 2 * small_share) << scene;
    const Usage usage = skipped_usage(predictive);
    EXPECT_LE(usage.bound, 1.0) << scene;
    EXPECT_LE(usage.range, 1.0) << scene;
    // The same decisions; but a face full sampling measured may have had its pattern
    // densified where prediction skipped it: the two then read other samples there until
    // prediction measures it (PredictiveDecisions below). Seen (when patterns were numbered in
    // the order they were drawn, so that all later ones differed): sinc 3420 vs 3414.
    EXPECT_NEAR(static_cast<double>(p.triangles), static_cast<double>(f.triangles),
                0.01 * static_cast<double>(f.triangles))
        << scene;
    const auto dense = test::dense_error(predictive.adapter->mesh(), *predictive.surface,
                                         10.0 * predictive.adapter->options().density, 5);
    EXPECT_LE(dense.max_error, 0.0025 * kSlack) << scene;
    RecordProperty(std::string(scene) + "_jump_measured",
                   std::to_string(static_cast<double>(p.faces_measured) / faces));
  }
}

// A static surface: nothing can change, so only the rotating fraction is measured, and the
// mesh is a fixed point as with full sampling.
TEST(PredictiveSampling, StaticSurfaceMeasuresOnlyTheRotatingFraction) {
  test::SceneRun run = test::start_scene("twist", options_with(0.002, Sampling::kPredictive), 0.3);
  const std::size_t triangles = run.adapter->mesh().n_faces();
  for (int i = 0; i < 3; ++i) {
    const StepStats& s = run.adapter->step(0.3);
    EXPECT_EQ(s.triangles, triangles);
    EXPECT_EQ(s.splits + s.welds, 0u);
    EXPECT_LE(static_cast<double>(s.faces_measured),
              1.5 * static_cast<double>(triangles) / ErrorPredictor::kRotation);
  }
}

// The bound's quadratic part on implicit surfaces (and the scalar model's maximum):
// scalar_maximum against the largest
// |q| on a fine barycentric lattice (which, q being smooth, is within O(1/n^2) of the true
// maximum from below), for coefficients of both signs, zeros and ties.
TEST(PredictiveSampling, QuadraticPeakIsTheLargestValueOverTheTriangle) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<std::array<double, 3>> cases = {{1, 1, 1},  {1, 1, 0},   {1, -1, 0},   {1, -1, 1},
                                              {0, 0, 0},  {0, 0, 2},   {-1, -1, -1}, {3, 1, 1},
                                              {1, 2, -3}, {1e-9, 1, 1}};
  for (int i = 0; i < 200; ++i) cases.push_back({uniform(rng), uniform(rng), uniform(rng)});
  constexpr int n = 600;
  for (const auto& x : cases) {
    double lattice = 0.0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double b0 = static_cast<double>(i) / n, b1 = static_cast<double>(j) / n,
                     b2 = 1.0 - b0 - b1;
        lattice = std::max(lattice, std::abs(x[0] * b1 * b2 + x[1] * b2 * b0 + x[2] * b0 * b1));
      }
    const double scale = std::max({std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
    const double peak = scalar_maximum(x[0], x[1], x[2]);
    EXPECT_GE(peak, lattice - 1e-12) << x[0] << " " << x[1] << " " << x[2];
    EXPECT_LE(peak, lattice + 1e-5 * scale) << x[0] << " " << x[1] << " " << x[2];
  }
}

// Predictive sampling makes full sampling's split and weld decisions (issue 17: "The split and
// weld decisions are unchanged. Only needless re-evaluation goes."; error_predictor.h): run side
// by side, the two modes give the same mesh, face for face and vertex position for position (bit
// for bit), step after step.
//
// Where the theory lets them part: a face full sampling measured and densified (its samples did
// not fit the quadratic model, SampleStore::evaluate_faces) while prediction skipped it keeps its
// sparse pattern with prediction until it is next measured. The two runs then read different
// samples there, and a weld or split reading them may decide otherwise (either reading is within
// the skipped face's bound of its last measurement). A step whose meshes differ is therefore
// allowed only when some face's samples differed at its start, or one mode changed samples the
// other did not during it (a pattern drawn, a peak kept: SampleStore::sample_changes); the
// comparison ends there. On these runs that did not happen: every step's meshes were the same.

// Both meshes' faces (corner by corner) and vertex positions (bit for bit) are the same.
bool same_mesh(const Mesh48& a, const Mesh48& b) {
  if (a.n_faces() != b.n_faces() || a.face_capacity() != b.face_capacity() ||
      a.vertex_capacity() != b.vertex_capacity())
    return false;
  for (Face f : a.live_faces())
    if (!b.is_alive(f) || a.vertices(f) != b.vertices(f)) return false;
  for (Vertex v : a.live_vertices())
    if (!b.is_alive(v) || a.position(v) != b.position(v)) return false;
  return true;
}

// Live faces whose samples (their barycentric coordinates) differ between the two stores.
std::size_t faces_with_other_samples(const Mesh48& mesh, const SampleStore& a,
                                     const SampleStore& b) {
  std::size_t n = 0;
  std::vector<Vec3> xa, xb;
  for (Face f : mesh.live_faces()) {
    xa.clear();
    xb.clear();
    a.for_each_sample(f, [&](const Vec3& x, double) { xa.push_back(x); });
    b.for_each_sample(f, [&](const Vec3& x, double) { xb.push_back(x); });
    n += xa != xb;
  }
  return n;
}

struct Scenario {
  const char* scene;
  double threshold, t0, t1;
  int steps;
};

class PredictiveDecisions : public ::testing::TestWithParam<Scenario> {};

TEST_P(PredictiveDecisions, SameMeshAsFullSamplingWhileTheSamplesAreTheSame) {
  const Scenario c = GetParam();
  // The scenes' own criteria, as the CLI runs them; twist and capsule-bend start at t = 0.5
  // through their mild-time detour (large steps, Adapter::initialize).
  test::SceneRun predictive =
      test::start_scene(c.scene, options_with(c.threshold, Sampling::kPredictive), c.t0);
  test::SceneRun full =
      test::start_scene(c.scene, options_with(c.threshold, Sampling::kFull), c.t0);
  ASSERT_TRUE(same_mesh(predictive.adapter->mesh(), full.adapter->mesh()))
      << c.scene << ": the initial meshes differ";
  int compared = 0;
  std::size_t skipped = 0, steps_with_other_samples = 0;
  for (int i = 1; i <= c.steps; ++i) {
    const bool other_samples =
        faces_with_other_samples(full.adapter->mesh(), predictive.adapter->samples(),
                                 full.adapter->samples()) > 0;
    steps_with_other_samples += other_samples;
    const auto drawn = [&] {
      return static_cast<std::int64_t>(predictive.adapter->samples().sample_changes()) -
             static_cast<std::int64_t>(full.adapter->samples().sample_changes());
    };
    const std::int64_t drawn_before = drawn();
    const double t = c.t0 + (c.t1 - c.t0) * i / c.steps;
    const StepStats p = predictive.adapter->step(t);
    const StepStats f = full.adapter->step(t);
    skipped += f.faces_measured - p.faces_measured;
    if (!same_mesh(predictive.adapter->mesh(), full.adapter->mesh()) || p.splits != f.splits ||
        p.welds != f.welds) {
      const bool allowed = other_samples || drawn() != drawn_before;
      EXPECT_TRUE(allowed) << c.scene << ": the meshes part at step " << i << " (" << p.splits
                           << " / " << f.splits << " splits, " << p.welds << " / " << f.welds
                           << " welds), on the same samples";
      break;
    }
    ++compared;
  }
  // Not vacuous: most of the run was compared, and prediction skipped faces in it.
  EXPECT_GE(compared, c.steps * 3 / 4) << c.scene;
  EXPECT_GT(skipped, 0u) << c.scene;
  std::printf(
      "%s: %d of %d steps the same mesh (%zu of them with some face's samples not the same), "
      "%zu face measurements skipped\n",
      c.scene, compared, c.steps, steps_with_other_samples, skipped);
}

INSTANTIATE_TEST_SUITE_P(Scenes, PredictiveDecisions,
                         ::testing::Values(Scenario{"sinc", 0.002, 0.0, 1.0, 100},
                                           Scenario{"twist", 0.002, 0.5, 0.54, 40},
                                           Scenario{"capsule-bend", 0.002, 0.5, 0.54, 40}),
                         [](const ::testing::TestParamInfo<Scenario>& info) {
                           std::string name = info.param.scene;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace dynamesh
