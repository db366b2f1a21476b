// A capsule-bend step at a million triangles (issue 17; goal: <= 0.3 s on the 2-core
// machine). T = 9e-6 gives about 10^6 triangles (T = 9e-5 about 10^5, bench_adapter.cpp);
// t steps by 1e-3 from 0.5 after two warm-up steps (predictive sampling needs references).
// Reported: the median step's wall-clock and process CPU time (the CPU time is the work,
// what a shared machine's other load does not inflate) and each phase's median; the share of
// faces measured, the share measured only because their corners travelled or slid too far
// (ErrorPredictor::guarded) and the curvature radius the travel is held against, and the
// share with a vertex that moved more than a quarter of the face's shortest edge this step
// (the predictor's former guard, which measured all of those whatever their bound said); the
// steps that renumbered the mesh (AdaptOptions::renumber), the median renumbering time, and
// the share of scattered faces left (spatial_order.h); the share of curvature frames the
// smoothing reused (tangential_smoothing.cpp, frame_reusable).
//
// BM_CapsuleStepScaling: the same step at about 1.2e5, 3.3e5 and 6.2e5 triangles, to set its
// cost per triangle (step_ns_per_triangle, cpu_ns_per_triangle) against the 10^6 step's.
//
// BM_MillionFacePass: why the per-face passes cost what they do at this size. One pass over
// the adapted mesh's faces as the step's passes are built (read the three corners, a cross
// product, add it into the three corners' sums: compute_ring_centroids, find_bad_faces),
// timed in the mesh's own numbering (as the adapter keeps it), in the same mesh renumbered
// afresh along the Morton curve, and in random order (a numbering without locality).
//
// BM_MillionStepEvaluations: how much of that step is evaluating the surface, the part no
// bookkeeping can remove. The same scene through CountingSurface (counting_surface.h) counts the
// evaluations of each kind a step asks for; each kind is then timed alone at the mesh's
// vertices with the same threads, and their sum per step is the step's evaluation time, to be
// set against BM_MillionTriangleStep's median (the counting wrapper's atomics would slow a
// timed step, so this benchmark does not time one).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/mesh/spatial_order.h"
#include "core/surface/scene_registry.h"
#include "median.h"
#include "process_cpu_time.h"
#include "tests/support/counting_surface.h"

namespace dynamesh {
namespace {

// Capsule-bend adapted at t = 0.5 to `threshold`, then stepped twice by 1e-3 (to 0.502).
struct MillionScene {
  explicit MillionScene(double threshold,
                        std::unique_ptr<Surface> scene = make_scene("capsule-bend"))
      : surface(std::move(scene)) {
    surface->set_time(0.5);
    AdaptOptions o;
    o.threshold = threshold;
    o.epsilon = threshold / 4;
    o.max_triangles = 4'000'000;
    adapter = std::make_unique<Adapter>(*surface, o, default_criteria("capsule-bend", 0.0, o, 0.0));
    adapter->initialize();
    for (int i = 0; i < 2; ++i) adapter->step(t += 1e-3);
  }
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
  double t = 0.5;
};

// Faces with a corner that moved more than a quarter of the face's shortest edge since
// `before` (new corners count as moved), as a share of all faces.
double moved_share(const Mesh48& mesh, const std::vector<Vec3>& before) {
  std::size_t moved = 0;
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    double shortest = 1e300, farthest = 0.0;
    for (int e = 0; e < 3; ++e) {
      shortest = std::min(shortest,
                          (mesh.position(v[(e + 1) % 3]) - mesh.position(v[(e + 2) % 3])).norm());
      farthest = std::max(farthest, v[e].idx < before.size()
                                        ? (mesh.position(v[e]) - before[v[e].idx]).norm()
                                        : 1e300);
    }
    moved += farthest > 0.25 * shortest;
  }
  return static_cast<double>(moved) / static_cast<double>(mesh.n_faces());
}

void BM_MillionTriangleStep(benchmark::State& state, double threshold) {
  MillionScene scene(threshold);
  Adapter& adapter = *scene.adapter;
  std::vector<double> wall, cpu, project, smooth, sample, weld, split;
  double measured = 0, faces = 0, moved = 0, guarded = 0, renumbered = 0, reused = 0, vertices = 0;
  std::vector<double> renumber;
  for (auto _ : state) {
    const std::vector<Vec3> before = adapter.mesh().positions();
    const double cpu0 = process_cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    const StepStats& st = adapter.step(scene.t += 1e-3);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    cpu.push_back(process_cpu_seconds() - cpu0);
    project.push_back(st.seconds.project);
    smooth.push_back(st.seconds.smooth);
    sample.push_back(st.seconds.sample);
    weld.push_back(st.seconds.weld);
    split.push_back(st.seconds.split);
    renumber.push_back(st.seconds.renumber);
    renumbered += st.renumbered;
    measured += static_cast<double>(st.faces_measured);
    reused += static_cast<double>(st.frames_reused);
    vertices += static_cast<double>(st.vertices);
    guarded += static_cast<double>(adapter.predictor().guarded());
    faces += static_cast<double>(st.triangles);
    moved += moved_share(adapter.mesh(), before) * static_cast<double>(st.triangles);
  }
  state.counters["triangles"] = static_cast<double>(adapter.mesh().n_faces());
  state.counters["median_step_ms"] = 1e3 * median(wall);
  state.counters["median_cpu_ms"] = 1e3 * median(cpu);
  // Per triangle (BM_CapsuleStepScaling): whether a larger mesh costs more per element.
  state.counters["step_ns_per_triangle"] =
      1e9 * median(wall) / (faces / static_cast<double>(wall.size()));
  state.counters["cpu_ns_per_triangle"] =
      1e9 * median(cpu) / (faces / static_cast<double>(cpu.size()));
  state.counters["project_ms"] = 1e3 * median(project);
  state.counters["smooth_ms"] = 1e3 * median(smooth);
  state.counters["sample_ms"] = 1e3 * median(sample);
  state.counters["weld_ms"] = 1e3 * median(weld);
  state.counters["split_ms"] = 1e3 * median(split);
  state.counters["renumber_ms"] = 1e3 * median(renumber);
  state.counters["renumbered_steps"] = renumbered;
  state.counters["scattered_share"] = scattered_face_share(adapter.mesh());
  state.counters["measured_share"] = measured / faces;
  state.counters["frames_reused_share"] = reused / vertices;
  state.counters["moved_share"] = moved / faces;
  state.counters["guarded_share"] = guarded / faces;
  state.counters["curvature_radius"] = adapter.predictor().curvature_radius();
}

BENCHMARK_CAPTURE(BM_MillionTriangleStep, capsule_T9e - 6, 9e-6)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// The same step on smaller meshes of the same scene (about 1.2e5, 3.3e5 and 6.2e5 triangles):
// its cost per triangle against BM_MillionTriangleStep's. Flat, the step is as dear per element
// at 10^6 as where its data fits in the cache, and the 10^6 goal is a matter of the work per
// element, not of memory (README, "The cost per triangle does not grow with the mesh").
void BM_CapsuleStepScaling(benchmark::State& state, double threshold) {
  BM_MillionTriangleStep(state, threshold);
}
BENCHMARK_CAPTURE(BM_CapsuleStepScaling, capsule_T9e - 5, 9e-5)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);
BENCHMARK_CAPTURE(BM_CapsuleStepScaling, capsule_T3e - 5, 3e-5)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_CapsuleStepScaling, capsule_T1_5e - 5, 1.5e-5)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// Seconds per call of one kind of evaluation, each thread taking its share of `points` (the
// best of three sweeps: what the evaluations cost when the step makes them, not the load).
template <class Evaluate>
double seconds_per_call(const std::vector<Vec3>& points, const Evaluate& evaluate) {
  const auto n = static_cast<std::int64_t>(points.size());
  double best = 1e300;
  for (int sweep = 0; sweep < 3; ++sweep) {
    double sink = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) reduction(+ : sink)
    for (std::int64_t i = 0; i < n; ++i) sink += evaluate(points[static_cast<std::size_t>(i)]);
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(sink);
  }
  return best / static_cast<double>(n);
}

void BM_MillionStepEvaluations(benchmark::State& state, double threshold) {
  std::unique_ptr<Surface> scene = make_scene("capsule-bend");
  auto* implicit = dynamic_cast<ImplicitSurface*>(scene.get());
  if (implicit == nullptr) {
    state.SkipWithError("capsule-bend is not implicit");
    return;
  }
  scene.release();
  auto owned = std::make_unique<CountingSurface>(std::unique_ptr<ImplicitSurface>(implicit));
  CountingSurface& counting = *owned;
  MillionScene million(threshold, std::move(owned));
  using Kind = CountingSurface::Kind;
  std::array<double, CountingSurface::kKinds> per_step{};
  double steps = 0.0;
  for (auto _ : state) {
    counting.reset_counts();
    million.adapter->step(million.t += 1e-3);
    for (int k = 0; k < CountingSurface::kKinds; ++k)
      per_step[static_cast<std::size_t>(k)] += static_cast<double>(counting.count(Kind(k)));
    steps += 1.0;
  }
  for (double& c : per_step) c /= steps;
  // Each kind timed at the vertices, on the surface at the last step's time.
  const ImplicitSurface& s = counting.wrapped();
  std::vector<Vec3> points;
  for (const Vertex v : million.adapter->mesh().live_vertices())
    points.push_back(million.adapter->mesh().position(v));
  std::array<double, CountingSurface::kKinds> cost{};
  cost[Kind::kValue] = seconds_per_call(points, [&](const Vec3& p) { return s.value(p); });
  cost[Kind::kValueGradient] = seconds_per_call(points, [&](const Vec3& p) {
    Vec3 g;
    return s.value_gradient(p, g) + g[0];
  });
  cost[Kind::kHessian] = seconds_per_call(points, [&](const Vec3& p) {
    Vec3 g;
    Mat3 h;
    return s.value_gradient_hessian(p, g, h) + h(0, 0);
  });
  cost[Kind::kToRest] = seconds_per_call(points, [&](const Vec3& p) { return s.to_rest(p)[0]; });
  cost[Kind::kFromRest] =
      seconds_per_call(points, [&](const Vec3& p) { return s.from_rest(p)[0]; });
  const char* names[CountingSurface::kKinds] = {"value", "value_gradient", "hessian", "to_rest",
                                                "from_rest"};
  double seconds = 0.0;
  for (std::size_t k = 0; k < per_step.size(); ++k) {
    state.counters[std::string(names[k]) + "_per_step"] = per_step[k];
    state.counters[std::string(names[k]) + "_ns"] = 1e9 * cost[k];
    seconds += per_step[k] * cost[k];
  }
  state.counters["triangles"] = static_cast<double>(million.adapter->mesh().n_faces());
  state.counters["vertices"] = static_cast<double>(points.size());
  state.counters["evaluation_ms_per_step"] = 1e3 * seconds;
}

BENCHMARK_CAPTURE(BM_MillionStepEvaluations, capsule_T9e - 6, 9e-6)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// The pass: each face's (area-weighted) normal added into its three corners' sums.
void face_pass(const Triangles& faces, const std::vector<Vec3>& p, std::vector<Vec3>& sum) {
  std::fill(sum.begin(), sum.end(), Vec3::Zero());
  for (const auto& f : faces) {
    const Vec3 n = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
    for (const std::uint32_t v : f) sum[v] += n;
  }
}

void BM_MillionFacePass(benchmark::State& state, double threshold) {
  MillionScene scene(threshold);
  const Mesh48& mesh = scene.adapter->mesh();
  Triangles own;
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    own.push_back({v[0].idx, v[1].idx, v[2].idx});
  }
  const std::vector<Vec3>& p = mesh.positions();
  // The same mesh renumbered afresh along the Morton curve (spatial_order.h).
  const Renumbering r = spatial_renumbering(mesh);
  std::vector<Vec3> morton_p(p);
  renumber_elements(morton_p, r.vertex, r.n_vertices);
  Triangles morton(r.n_faces);
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    morton[r.face[f.idx]] = {r.vertex[v[0].idx], r.vertex[v[1].idx], r.vertex[v[2].idx]};
  }
  // And in random order: what a numbering without locality costs (the split order was
  // close to it: corners 270,000 ids apart on average at 10^6 triangles).
  std::mt19937 rng(1);
  std::vector<std::uint32_t> shuffle(p.size());
  std::iota(shuffle.begin(), shuffle.end(), 0u);
  std::shuffle(shuffle.begin(), shuffle.end(), rng);
  std::vector<Vec3> random_p(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) random_p[shuffle[i]] = p[i];
  Triangles random = own;
  for (auto& f : random)
    for (auto& v : f) v = shuffle[v];
  std::shuffle(random.begin(), random.end(), rng);
  std::vector<Vec3> sum(p.size());
  std::vector<double> own_s, morton_s, random_s;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    face_pass(own, p, sum);
    own_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(sum.data());
    t0 = std::chrono::steady_clock::now();
    face_pass(morton, morton_p, sum);
    morton_s.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(sum.data());
    t0 = std::chrono::steady_clock::now();
    face_pass(random, random_p, sum);
    random_s.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(sum.data());
  }
  double spread = 0.0;
  for (const auto& f : own)
    spread += *std::max_element(f.begin(), f.end()) - *std::min_element(f.begin(), f.end());
  state.counters["triangles"] = static_cast<double>(own.size());
  state.counters["own_numbering_ms"] = 1e3 * median(own_s);
  state.counters["morton_ms"] = 1e3 * median(morton_s);
  state.counters["random_order_ms"] = 1e3 * median(random_s);
  // What one renumbering of the adapter costs at this size (the order, the mesh, and every
  // listener's data: the sample pool is rewritten in the new face order), process CPU time.
  const double cpu0 = process_cpu_seconds();
  scene.adapter->renumber(spatial_renumbering(mesh));
  state.counters["renumber_cpu_ms"] = 1e3 * (process_cpu_seconds() - cpu0);
  state.counters["scattered_share"] = scattered_face_share(mesh);
  state.counters["corner_id_spread"] = spread / static_cast<double>(own.size());
}

BENCHMARK_CAPTURE(BM_MillionFacePass, capsule_T9e - 6, 9e-6)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);

}  // namespace
}  // namespace dynamesh
