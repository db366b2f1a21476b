// Every frame of a strong motion is an embedded, well-shaped mesh (issue 13; DESIGN.md,
// "Quality bars"): each published frame is judged by the exact CGAL test of
// tests/support/mesh_validity.h (self-intersecting triangle pairs, manifoldness, smallest
// angle) and by an independent dense measurement of its error -- never by the adapter's own
// counters. The motions are the issue's: twist with 3 turns in 10 steps, capsule-bend bent
// 270 degrees in 8 steps, sinc at amplitude 0.9 in 8 steps, mri down and back up; and a sweep
// there and back returns close to its starting triangle count on every scene, cycle after
// cycle.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "core/surface/volume/mri_layers.h"
#include "dense_error.h"
#include "stats_table.h"
#include "tests/support/mesh_validity.h"

namespace dynamesh {
namespace {

struct MotionRun {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
  AdaptOptions options;
};

// The scene as the CLI builds it (apply_scene_defaults): the scene's suggested threshold and
// density unless given, eps = T / 4.
MotionRun start(const std::string& scene, const ParameterOverrides& overrides, double threshold,
                const AdaptOptions& base = {}) {
  MotionRun run;
  run.surface = make_scene(scene, overrides);
  SceneInfo info;
  for (const SceneInfo& i : list_scenes())
    if (i.name == scene) info = i;
  run.options = base;
  run.options.threshold = threshold > 0 ? threshold : info.suggested_threshold;
  run.options.epsilon = run.options.threshold / 4;
  run.options.density = info.suggested_density;
  double edge_length = 0.0;
  for (const SurfaceParameter& p : run.surface->parameters())
    if (p.name == "L") edge_length = p.value;
  run.adapter = std::make_unique<Adapter>(*run.surface, run.options,
                                          default_criteria(scene, edge_length, run.options, 0.0));
  run.adapter->initialize();
  return run;
}

struct FrameBounds {
  double min_angle_deg = 10.0;
  bool closed = true;
  double dense_density = 0.0;  // 0: no dense error measurement
};

// What sparse sampling can miss (test_adapter.cpp, kSparseSamplingSlack): 10%.
constexpr double kSparseSamplingSlack = 1.10;

void expect_frame_ok(const MotionRun& run, const FrameBounds& bounds, const std::string& where) {
  const Mesh48& mesh = run.adapter->mesh();
  ASSERT_TRUE(mesh.check().ok()) << where << ": " << mesh.check().summary();
  const test::MeshValidity v = test::check_mesh_validity(mesh);
  EXPECT_TRUE(bounds.closed ? v.embedded_closed_manifold() : v.embedded_manifold())
      << where << ": " << v.describe();
  EXPECT_GE(v.min_angle_deg, bounds.min_angle_deg) << where << ": " << v.describe();
  if (bounds.dense_density > 0) {
    const auto dense = test::dense_error(mesh, *run.surface, bounds.dense_density, 7);
    const double bound = (run.options.threshold + run.options.epsilon) * kSparseSamplingSlack;
    EXPECT_LE(dense.max_error, bound) << where << ": dense error at " << dense.worst.transpose();
  }
}

// Steps through `times` (the first is where the run starts), judging every frame; returns the
// sub-steps the engine took.
int run_frames(MotionRun& run, const std::vector<double>& times, int steps_per_segment,
               const FrameBounds& bounds, const std::string& name) {
  int substeps = 0;
  expect_frame_ok(run, bounds, name + " initial frame");
  for (std::size_t s = 1; s < times.size(); ++s)
    for (int i = 1; i <= steps_per_segment; ++i) {
      const double t = times[s - 1] + (times[s] - times[s - 1]) * i / steps_per_segment;
      substeps += run.adapter->step(t).substeps;
      expect_frame_ok(run, bounds, name + " t=" + std::to_string(t));
      if (::testing::Test::HasFailure()) return substeps;
    }
  return substeps;
}

// Judges the frames a CLI run exported to `frames` (frame_00000.ply .. frame_<last>.ply) as they
// lie on disk: each an embedded closed manifold with no angle below `min_angle_deg`. Returns
// each frame's smallest angle.
std::vector<double> expect_exported_frames_ok(const std::filesystem::path& frames, int last,
                                              double min_angle_deg) {
  std::vector<double> smallest;
  for (int step = 0; step <= last; ++step) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.ply", step);
    const test::MeshValidity v = test::check_mesh_validity_of_file((frames / name).string());
    EXPECT_TRUE(v.embedded_closed_manifold()) << name << ": " << v.describe();
    EXPECT_GE(v.min_angle_deg, min_angle_deg) << name << ": " << v.describe();
    smallest.push_back(v.min_angle_deg);
  }
  return smallest;
}

void expect_returns(const std::vector<double>& r, const std::string& scene) {
  for (std::size_t c = 0; c < r.size(); ++c) {
    EXPECT_GE(r[c], 0.85) << scene << " cycle " << c + 1;
    EXPECT_LE(r[c], 1.2) << scene << " cycle " << c + 1;
  }
  EXPECT_NEAR(r[2] / r[1], 1.0, 0.05) << scene << ": the third cycle drifts from the second";
}

// Three cycles through the binary (`--keyframes 0,1,0,1,0,1,0`): the triangle counts at the
// three returns to t = 0 over the starting count, from the run's JSON summary.
std::vector<double> keyframe_returns(const test::CliRun& r) {
  std::vector<double> returns;
  const auto& k = r.json["keyframe_triangles"];
  if (!k.is_array() || k.size() != 7) {
    ADD_FAILURE() << "keyframe_triangles: " << r.out;
    return {0.0, 0.0, 0.0};
  }
  for (std::size_t i : {2u, 4u, 6u}) returns.push_back(k[i].get<double>() / k[0].get<double>());
  return returns;
}

// --- strong motions, every frame -----------------------------------------------------------

// The issue measured twist at T = 0.002 (its note has that run: every frame clean, 41k
// triangles at t = 1). At T = 0.004 the same motion without sub-steps and repair ends with 4691
// self-intersecting pairs and a smallest angle of 0.02 degrees (and below the 10-degree floor well
// before), and the test stays within seconds.
TEST(MotionFrames, TwistThreeTurnsInTenSteps) {
  MotionRun run = start("twist", {{"turns", 3.0}}, 0.004);
  const FrameBounds bounds{10.0, true, 4.0 * run.options.density};
  const int substeps = run_frames(run, {0.0, 1.0}, 10, bounds, "twist");
  EXPECT_GT(substeps, 10) << "the motion is strong: the engine must have sub-stepped";
}

// The same bound whatever the sample jitter, not for one seed: every frame of that motion is
// measured densely (the CGAL checks are the test above's) for sampling seeds 1-8. Before faces
// near the bound had their edges searched for the peak (sample_store.h, EdgePeak), the
// estimate under-read the true peak by up to 33% on the twisted sides: a denser measurement
// than this one found 1.09-1.18 (T + eps) over the frames of seeds 1-8, and this measurement
// failed seeds 1, 3, 4, 6 and 7 of 1-7 and the test above at seed 1 (1.106), while on main's
// smoothing the test above passed its one seed by luck (seeds 2, 5, 7 failed).
class TwistSampleSeeds : public ::testing::TestWithParam<int> {};

TEST_P(TwistSampleSeeds, EveryFrameWithinDenseBound) {
  AdaptOptions base;
  base.seed = static_cast<std::uint64_t>(GetParam());
  MotionRun run = start("twist", {{"turns", 3.0}}, 0.004, base);
  const double bound = (run.options.threshold + run.options.epsilon) * kSparseSamplingSlack;
  for (int i = 0; i <= 10; ++i) {
    if (i > 0) run.adapter->step(i / 10.0);
    const auto dense =
        test::dense_error(run.adapter->mesh(), *run.surface, 4.0 * run.options.density, 7);
    EXPECT_LE(dense.max_error, bound)
        << "seed " << GetParam() << " t=" << i / 10.0 << ": dense error "
        << dense.max_error / (run.options.threshold + run.options.epsilon) << " (T + eps) at "
        << dense.worst.transpose();
  }
}

INSTANTIATE_TEST_SUITE_P(MotionFrames, TwistSampleSeeds, ::testing::Range(1, 9));

TEST(MotionFrames, CapsuleBent270DegreesInEightSteps) {
  MotionRun run = start("capsule-bend", {{"bend", 1.5 * std::numbers::pi}}, 0.0);
  const FrameBounds bounds{10.0, true, 4.0 * run.options.density};
  run_frames(run, {0.0, 1.0}, 8, bounds, "capsule-bend");
}

TEST(MotionFrames, SincAmplitude09InEightSteps) {
  MotionRun run = start("sinc", {{"alpha", 0.9}}, 0.0);
  const FrameBounds bounds{10.0, false, 4.0 * run.options.density};
  run_frames(run, {0.0, 1.0}, 8, bounds, "sinc");
}

// The same three strong motions with settled vertices left in place (SmoothingOptions::
// settled_offset, an option): every frame still an embedded manifold (CGAL), no angle below the
// floor, the dense error within its bound. The frames are judged, not only the last.
TEST(MotionFrames, SettledVerticesKeepEveryFrameEmbedded) {
  AdaptOptions base;
  base.smoothing.settled_offset = 0.01;
  {
    MotionRun run = start("twist", {{"turns", 3.0}}, 0.004, base);
    run_frames(run, {0.0, 1.0}, 10, {10.0, true, 4.0 * run.options.density}, "settled twist");
  }
  {
    MotionRun run = start("capsule-bend", {{"bend", 1.5 * std::numbers::pi}}, 0.0, base);
    run_frames(run, {0.0, 1.0}, 8, {10.0, true, 4.0 * run.options.density}, "settled capsule");
  }
  {
    MotionRun run = start("sinc", {{"alpha", 0.9}}, 0.0, base);
    run_frames(run, {0.0, 1.0}, 8, {10.0, false, 4.0 * run.options.density}, "settled sinc");
  }
}

// Colin27, T = 0.5 mm (the scene's default), through the real binary. The sweep is
// 0 -> 20 -> 0 mm in 20 + 20 steps; without sub-steps and repair 0 -> 9 mm in 12 steps already
// self-intersects (5 pairs), so this test runs 0 -> 10 -> 0 mm in 10 + 10 steps, the same
// speed per step as the sweep, three times (`--keyframes 0,1,0,1,0,1,0`): every one of
// the 61 exported frames is judged as it lies on disk (embedded, closed, smallest angle >= 5
// degrees), and the counts at the keyframes give the return to start (the mesh grew 3.2x over
// one 0 -> 15 -> 0 mm cycle before). One process, one segmentation and distance transform:
// this replaced a library run that judged only the first cycle (26 s CPU then, 29 s now).
TEST(MotionFrames, MriDownAndBackUpThreeTimes) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const std::filesystem::path dir = test::cli_scratch("mri_cycles");
  const test::CliRun r =
      test::run_cli({"--scene", "mri", "--param", "depth_max=10", "--keyframes", "0,1,0,1,0,1,0",
                     "--steps", "10", "--export", (dir / "frames").string(), "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_exported_frames_ok(dir / "frames", 60, 5.0);
  const std::vector<double> returns = keyframe_returns(r);
  expect_returns(returns, "mri");
  RecordProperty("mri_returns", std::to_string(returns[0]) + " " + std::to_string(returns[1]) +
                                    " " + std::to_string(returns[2]));
  std::filesystem::remove_all(dir);
}

// The issue's own mri run, 0 -> 20 -> 0 mm in 20 + 20 steps (the test above sweeps half as
// deep at the same speed per step, three times), with predictive and with full sampling: two
// trajectories through the same motion. Every one of the 41 exported frames is judged as it
// lies on disk. Of all the strong motions this one's smallest angle was the closest to its
// bar, and a matter of luck: 5.23 degrees predictive, 4.9985 full (at 0 mm on the way back
// up), before the fold repair searched around vertices the centroid could not move
// (fold_repair.cpp, relax_vertex) and the frame was screened again after the splits that
// follow a repair (Adapter::publish_repaired); with both, 10.0014 and 10.0039 (2026-11-24).
// And whatever is left below the repair's 10-degree floor is reported in the stats
// (slivers_left), never hidden.
class MriDownTwentyMillimetresAndBack : public ::testing::TestWithParam<const char*> {};

TEST_P(MriDownTwentyMillimetresAndBack, EveryFrameEmbeddedAndReported) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const std::filesystem::path dir = test::cli_scratch(std::string("mri_twenty_") + GetParam());
  const test::CliRun r =
      test::run_cli({"--scene", "mri", "--param", "depth_max=20", "--keyframes", "0,1,0", "--steps",
                     "20", "--sampling", GetParam(), "--export", (dir / "frames").string(),
                     "--stats", (dir / "stats.csv").string(), "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<double> smallest = expect_exported_frames_ok(dir / "frames", 40, 5.0);
  const test::StatsTable stats(dir / "stats.csv");
  const std::vector<std::string> folds = stats.column("folds_left"),
                                 slivers = stats.column("slivers_left");
  ASSERT_EQ(slivers.size(), smallest.size());
  ASSERT_EQ(folds.size(), smallest.size());
  // The file holds single-precision positions: a face at 10 degrees may read a little less.
  for (std::size_t i = 0; i < smallest.size(); ++i) {
    if (smallest[i] >= 9.99) continue;
    EXPECT_GT(std::stoi(folds[i]) + std::stoi(slivers[i]), 0)
        << "frame " << i << " has an angle of " << smallest[i] << " degrees, reported as none";
  }
  RecordProperty("smallest_angle_deg",
                 std::to_string(*std::min_element(smallest.begin(), smallest.end())));
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(MotionFrames, MriDownTwentyMillimetresAndBack,
                         ::testing::Values("predictive", "full"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

// The same through the real binary: dynamesh-cli exports every frame of a strong twist (3 turns
// in 5 steps at T = 0.006: without the safeguards its last frame's smallest angle is 7.3
// degrees), and each exported file is judged as it lies on disk; the stats CSV reports the
// sub-steps taken and no fold or sliver left in any frame.
TEST(MotionFrames, CliExportsOnlyEmbeddedFrames) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("dynamesh_motion_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string command =
      std::string(DYNAMESH_BINARY_DIR) +
      "/dynamesh-cli run --scene twist --param turns=3 --threshold 0.006 --steps 5 --stats " +
      (dir / "stats.csv").string() + " --export " + (dir / "frames").string() +
      " --export-every 1 --quiet > " + (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  expect_exported_frames_ok(dir / "frames", 5, 10.0);
  const test::StatsTable stats(dir / "stats.csv");
  const std::vector<std::string> substeps = stats.column("substeps"),
                                 folds = stats.column("folds_left"),
                                 slivers = stats.column("slivers_left");
  int most_substeps = 0;
  for (std::size_t i = 0; i < substeps.size(); ++i) {
    most_substeps = std::max(most_substeps, std::stoi(substeps[i]));
    EXPECT_EQ(folds[i], "0") << "step " << i;
    EXPECT_EQ(slivers[i], "0") << "step " << i;
  }
  EXPECT_GT(most_substeps, 1) << "a 3-turn twist in 5 steps must be sub-stepped";
  fs::remove_all(dir);
}

// A still frame at an extreme time, initialised there: twist with 3 turns at t = 1. Refined
// directly from its twisted base mesh it was not embedded (T = 0.002: 1.67M self-intersecting
// pairs, smallest angle 0.72 degrees; T = 0.004: 851 690 pairs, 1.01 degrees); the adapter now
// adapts the untwisted bar (Surface::mild_time) and follows the twist to t = 1 before the first
// frame is published.
TEST(MotionFrames, TwistInitialisedAtThreeTurns) {
  std::unique_ptr<Surface> surface = make_scene("twist", {{"turns", 3.0}});
  surface->set_time(1.0);
  AdaptOptions options;
  options.threshold = 0.004;
  options.epsilon = options.threshold / 4;
  options.density = 2000.0;
  MotionRun run{std::move(surface), nullptr, options};
  run.adapter = std::make_unique<Adapter>(*run.surface, options,
                                          default_criteria("twist", 0.0, options, 0.0));
  const StepStats& stats = run.adapter->initialize();
  EXPECT_EQ(run.surface->time(), 1.0);
  EXPECT_EQ(stats.step, 0);
  expect_frame_ok(run, {10.0, true, 4.0 * options.density}, "twist initialised at t = 1");
}

// --- return to start --------------------------------------------------------------------

// A sweep t: 0 -> 1 -> 0 returns to the fresh mesh only if the fresh mesh is a state the
// motion itself leaves behind. Two asymmetries broke that (criteria.h, adapt_options.h):
// - Welds stopped at the paper's T - eps (and L 2^(-1/4)) while the first refinement stopped
//   at T (L): a sweep that ends with welds kept regions a level finer. Counts after cycles 1,
//   2, 3 over the start were sphere 1.27 1.33 1.35 and capsule-bend 1.12 1.25 1.24.
// - The first mesh was never smoothed, while a motion's smoothing moves vertices onto the
//   curvature (the twisted bar's rims), where fewer triangles meet the bound: twist came back
//   0.84 0.82 0.87 (its caps 912 -> 506 triangles), with the weld bound already at T.
// With the weld bound at the first refinement's target and 20 rounds of relaxation at
// initialisation (seen failing without either): sphere 1.04 1.04 1.06, capsule-bend 1.03
// 1.08 1.04, sinc 1.00, twist 1.02 0.99 0.96 (seeds 2 and 3 in the library: 1.01 0.97 0.96
// and 1.01 0.99 0.99); mri in MriDownAndBackUpThreeTimes.
// Driven through the real binary, as a user would run it (scene defaults, 10 steps a segment);
// the same command with --no-smooth (no relaxation either) returns twist at 0.83 0.98 0.91.
void expect_scene_returns(const char* scene) {
  const test::CliRun r =
      test::run_cli({"--scene", scene, "--keyframes", "0,1,0,1,0,1,0", "--steps", "10", "--quiet"});
  ASSERT_EQ(r.status, 0) << scene << ": " << r.err;
  const std::vector<double> returns = keyframe_returns(r);
  expect_returns(returns, scene);
  ::testing::Test::RecordProperty(std::string(scene) + "_returns",
                                  std::to_string(returns[0]) + " " + std::to_string(returns[1]) +
                                      " " + std::to_string(returns[2]));
}

TEST(MotionFrames, AnalyticScenesReturnToStart) {
  for (const char* scene : {"sphere", "capsule-bend", "sinc", "twist"}) expect_scene_returns(scene);
}

}  // namespace
}  // namespace dynamesh
