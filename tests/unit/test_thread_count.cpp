// The same frames whatever the thread count (issue 13): a run with one OpenMP thread and the
// same run with two give bitwise the same positions, faces and statistics at every step.
// Loops shorter than kParallelMin run on one thread (core/parallel.h), so every run here has
// more than that many faces and vertices, or it could not fail. What failed before the fix
// (main cea65ba, 2026-11-24; every test here failed at its initial mesh, step 0): the ring sums
// of the tangential smoothing (each thread's partial sums added: other last bits on the vertices
// where two threads' faces meet), and the mean sampled error (an OpenMP reduction(+)).
#include <gtest/gtest.h>

#include <omp.h>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/parallel.h"
#include "core/surface/scene_registry.h"
#include "core/surface/volume/mri_layers.h"

namespace dynamesh {
namespace {

// A step's published state, bit for bit: every live vertex (id and position), every live face
// (id and corners), and every statistic but the timings.
struct Frame {
  std::vector<std::uint64_t> vertices, faces;
  std::vector<std::pair<std::string, std::uint64_t>> stats;
};

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

Frame frame_of(const Adapter& adapter, const StepStats& s) {
  Frame f;
  const Mesh48& mesh = adapter.mesh();
  for (Vertex v : mesh.live_vertices()) {
    f.vertices.push_back(v.idx);
    for (int k = 0; k < 3; ++k) f.vertices.push_back(bits(mesh.position(v)[k]));
  }
  for (Face face : mesh.live_faces()) {
    f.faces.push_back(face.idx);
    for (Vertex v : mesh.vertices(face)) f.faces.push_back(v.idx);
  }
  auto add = [&](const char* name, auto value) {
    if constexpr (std::is_floating_point_v<decltype(value)>)
      f.stats.emplace_back(name, bits(value));
    else
      f.stats.emplace_back(name, static_cast<std::uint64_t>(value));
  };
  add("step", s.step);
  add("time", s.time);
  add("triangles", s.triangles);
  add("vertices", s.vertices);
  add("splits", s.splits);
  add("welds", s.welds);
  add("max_error", s.max_error);
  add("mean_error", s.mean_error);
  add("samples", s.samples);
  add("faces_measured", s.faces_measured);
  add("vertices_kept", s.vertices_kept);
  add("kept_fraction", s.kept_fraction);
  add("survivor_displacement_mean", s.survivor_displacement_mean);
  add("survivor_displacement_max", s.survivor_displacement_max);
  add("smoothing_moved", s.smoothing_moved);
  add("smoothing_reverted", s.smoothing_reverted);
  add("frames_reused", s.frames_reused);
  add("evaluations_reused", s.evaluations_reused);
  add("splits_refused", s.splits_refused);
  add("pathological_welds", s.pathological_welds);
  add("projection_failures", s.projection_failures);
  add("substeps", s.substeps);
  add("motion_strain", s.motion_strain);
  add("folds_found", s.folds_found);
  add("slivers_found", s.slivers_found);
  add("repair_moves", s.repair_moves);
  add("folds_left", s.folds_left);
  add("slivers_left", s.slivers_left);
  add("budget_hit", s.budget_hit);
  add("sample_budget_hit", s.sample_budget_hit);
  add("topology_events", s.topology_events.size());
  add("local_repairs", s.local_repairs);
  add("repair_faces_replaced", s.repair_faces_replaced);
  add("repair_spacing", s.repair_spacing);
  add("splits_held", s.splits_held);
  add("held_depth", s.held_depth);
  add("rebuilt", s.rebuilt);
  add("renumbered", s.renumbered);
  add("folds_repaired", s.folds_repaired);
  add("folds_remeshed", s.folds_remeshed);
  return f;
}

struct RunSpec {
  std::string scene;
  ParameterOverrides overrides;
  double threshold = 0.0;  // 0: the scene's suggestion
  double density = 0.0;    // 0: the scene's suggestion
  Sampling sampling = Sampling::kPredictive;
  std::vector<double> times;  // the first is where the run starts
};

// The run `spec` with `threads` OpenMP threads (the scene built with them too); the thread
// count is restored afterwards. Options as the CLI sets them (apply_scene_defaults).
std::vector<Frame> run_with_threads(const RunSpec& spec, int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  std::vector<Frame> frames;
  {
    std::unique_ptr<Surface> surface = make_scene(spec.scene, spec.overrides);
    surface->set_time(spec.times.front());
    SceneInfo info;
    for (const SceneInfo& i : list_scenes())
      if (i.name == spec.scene) info = i;
    AdaptOptions options;
    options.threshold = spec.threshold > 0 ? spec.threshold : info.suggested_threshold;
    options.epsilon = options.threshold / 4;
    options.density = spec.density > 0 ? spec.density : info.suggested_density;
    options.sampling = spec.sampling;
    double edge_length = 0.0;
    for (const SurfaceParameter& p : surface->parameters())
      if (p.name == "L") edge_length = p.value;
    Adapter adapter(*surface, options, default_criteria(spec.scene, edge_length, options, 0.0));
    frames.push_back(frame_of(adapter, adapter.initialize()));
    for (std::size_t k = 1; k < spec.times.size(); ++k)
      frames.push_back(frame_of(adapter, adapter.step(spec.times[k])));
  }
  omp_set_num_threads(before);
  return frames;
}

// Equal frames, step by step; the first difference is described (which step, what differs).
void expect_same_frames(const RunSpec& spec, std::size_t min_faces) {
  const std::vector<Frame> one = run_with_threads(spec, 1), two = run_with_threads(spec, 2);
  ASSERT_EQ(one.size(), two.size());
  // Below kParallelMin faces every loop runs on one thread and this could not fail.
  EXPECT_GT(one.front().faces.size() / 4, min_faces) << spec.scene << ": too small a mesh";
  for (std::size_t k = 0; k < one.size(); ++k) {
    const Frame &a = one[k], &b = two[k];
    std::ostringstream where;
    where << spec.scene << " step " << k << " (t = " << spec.times[k] << ")";
    for (std::size_t i = 0; i < a.stats.size(); ++i)
      EXPECT_EQ(a.stats[i].second, b.stats[i].second)
          << where.str() << ": " << a.stats[i].first << " differs with 2 threads";
    EXPECT_TRUE(a.faces == b.faces) << where.str() << ": other faces with 2 threads ("
                                    << a.faces.size() / 4 << " and " << b.faces.size() / 4 << ")";
    if (a.vertices != b.vertices) {
      std::size_t differ = 0;
      for (std::size_t i = 0; i < std::min(a.vertices.size(), b.vertices.size()); ++i)
        differ += a.vertices[i] != b.vertices[i];
      ADD_FAILURE() << where.str() << ": other vertices with 2 threads (" << differ
                    << " coordinates or ids differ; " << a.vertices.size() / 4 << " vertices)";
    }
    if (::testing::Test::HasFailure()) return;  // later steps only repeat the divergence
  }
}

// Thresholds give every run more than 2 kParallelMin faces (so more than kParallelMin
// vertices too: the vertex loops run in parallel as well).
constexpr std::size_t kParallelFaces = 2 * kParallelMin;

// The smallest run that showed the bug: sphere, two small steps, 15k faces. Its initial mesh
// already differed (the initial relaxation smooths it), and so did every step after.
TEST(ThreadCount, SphereTwoStepsSameBits) {
  expect_same_frames({"sphere", {}, 0.0002, 0.0, Sampling::kPredictive, {0.0, 0.05, 0.1}},
                     kParallelFaces);
}

// Every analytic scene, three steps each of a strong motion (sub-steps, fold screens and
// repairs), with meshes larger than 2 kParallelMin; predictive sampling, and full on one.
// Blobs stops before its merge (t = 0.15): the steps through it take 7 s of CPU.
TEST(ThreadCount, AnalyticScenesSameBits) {
  expect_same_frames(
      {"twist", {{"turns", 3.0}}, 0.0012, 0.0, Sampling::kPredictive, {0.0, 0.05, 0.1, 0.15}},
      kParallelFaces);
  expect_same_frames({"capsule-bend", {}, 0.0007, 0.0, Sampling::kFull, {0.0, 0.3, 0.6, 0.9}},
                     kParallelFaces);
  expect_same_frames(
      {"sinc", {{"alpha", 0.9}}, 0.001, 0.0, Sampling::kPredictive, {0.1, 0.15, 0.2, 0.25}},
      kParallelFaces);
  expect_same_frames({"blobs", {}, 0.0009, 0.0, Sampling::kPredictive, {0.0, 0.05, 0.1}},
                     kParallelFaces);
}

// mri, the scene the divergence was found on, a few steps of its issue's speed per step (1 mm),
// at T = 0.4 mm (at 0.5 the mesh has 7k faces, 3.6k vertices: the vertex loops run serially).
// The volume's preparation runs with each thread count too.
TEST(ThreadCount, MriFewStepsSameBits) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  expect_same_frames(
      {"mri", {{"depth_max", 20.0}}, 0.4, 0.0, Sampling::kPredictive, {0.0, 0.05, 0.1, 0.15}},
      kParallelFaces);
}

}  // namespace
}  // namespace dynamesh
