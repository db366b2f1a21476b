// Smooth-animation step cost with and without the motion safeguards (issue 13): sub-stepping
// and fold repair must cost nothing measurable when the motion is small. Twist (default
// parameters, T = 0.008), 100 steps from t = 0 to 1 per iteration; argument 0 turns the
// safeguards off (the engine before them), 1 leaves them on. Counters: sub-steps taken beyond
// one per step, and the vertices moved by the fold repair, per step. Time is per 100 steps.
// Report CPU time (the machine is shared): `dynamesh_bench --benchmark_filter=Smooth`.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/adapt/motion_substeps.h"
#include "core/geometry/fold_repair.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

// Both benchmarks: twist at T = 0.008, eps = T / 4.
AdaptOptions twist_options() {
  AdaptOptions o;
  o.threshold = 0.008;
  o.epsilon = o.threshold / 4;
  return o;
}

// A twist surface and its adapter (not initialised); the surface must outlive the adapter.
struct TwistRun {
  explicit TwistRun(const AdaptOptions& o)
      : surface(make_scene("twist")),
        adapter(*surface, o, default_criteria("twist", 0.0, o, 0.0)) {}
  std::unique_ptr<Surface> surface;
  Adapter adapter;
};

void BM_SmoothAnimation(benchmark::State& state) {
  const bool safeguards = state.range(0) != 0;
  AdaptOptions o = twist_options();
  o.substeps.enabled = safeguards;
  o.fold_repair.enabled = safeguards;
  double extra_substeps = 0, repair_moves = 0, steps = 0, triangles = 0, measured = 0;
  for (auto _ : state) {
    state.PauseTiming();
    TwistRun run(o);
    run.adapter.initialize();
    state.ResumeTiming();
    for (int i = 1; i <= 100; ++i) {
      const StepStats& s = run.adapter.step(i / 100.0);
      extra_substeps += s.substeps - 1;
      repair_moves += static_cast<double>(s.repair_moves);
      triangles += static_cast<double>(s.triangles);
      measured += static_cast<double>(s.faces_measured);
      ++steps;
    }
    benchmark::DoNotOptimize(run.adapter.mesh().n_faces());
  }
  state.counters["extra_substeps_per_step"] = extra_substeps / steps;
  state.counters["repair_moves_per_step"] = repair_moves / steps;
  // The same work with and without the safeguards: the same meshes, the same faces measured.
  state.counters["triangles_per_step"] = triangles / steps;
  state.counters["measured_per_step"] = measured / steps;
}

BENCHMARK(BM_SmoothAnimation)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The safeguards' own work in a small-motion step, alone: what BM_SmoothAnimation/1 adds to
// /0 is this (the strain pass of the sub-step plan and the fold screen before publishing; the
// plan's surface evaluations are the projection's own, reused by the normal correction), far
// below that benchmark's run-to-run spread, so it is timed here on the same meshes. Setup (not
// timed): twist at T = 0.008 with the safeguards, 100 steps; each published mesh is kept, and
// each step's predicted displacements as the adapter plans them (rest points before the time
// changes, prediction after). Timed, per step: estimate_substeps on the mesh the step started
// from and the screen (find_bad_faces, its buffers kept as the adapter keeps them) on the mesh
// it published. Counter: bad faces found over the 100 steps, twice each (0: the clean path).
void BM_SafeguardChecks(benchmark::State& state) {
  struct Recorded {
    std::vector<Mesh48> meshes;  // [0]: the initial mesh; [i]: published at t = i / 100
    std::vector<std::vector<Vec3>> displacement;  // [i]: planned for the step to t = i / 100
    std::unique_ptr<TwistRun> run;
  };
  static const Recorded recorded = [] {
    Recorded r;
    AdaptOptions o = twist_options();
    r.run = std::make_unique<TwistRun>(o);
    Adapter& adapter = r.run->adapter;
    adapter.initialize();
    const SurfaceProbe probe(*r.run->surface);
    r.meshes.push_back(adapter.mesh());  // copies are only read (no listener is ever called)
    r.displacement.emplace_back();
    for (int i = 1; i <= 100; ++i) {
      std::vector<Vec3> rest(r.meshes.back().vertex_capacity());
      for (Vertex v : r.meshes.back().live_vertices())
        rest[v.idx] = probe.rest_point(r.meshes.back(), v);
      adapter.step(i / 100.0);
      r.displacement.emplace_back();
      predict_displacements(r.meshes.back(), probe, &rest, r.displacement.back());
      r.meshes.push_back(adapter.mesh());
    }
    return r;
  }();
  Surface& surface = *recorded.run->surface;
  const AdaptOptions o = twist_options();
  FoldScreenBuffers buffers;
  std::vector<Face> folded, slivers;
  double bad = 0, strain = 0;
  // Step i's checks, once untimed first: the adapter runs them on a mesh its step has just
  // walked (cache-warm), while the 100 recorded meshes (15 MB) cycled through here would each
  // come cold from memory.
  auto checks = [&](int i) {
    const MotionEstimate e =
        estimate_substeps(recorded.meshes[static_cast<std::size_t>(i - 1)],
                          recorded.displacement[static_cast<std::size_t>(i)], o.substeps);
    strain = std::max(strain, e.strain);
    surface.set_time(i / 100.0);
    find_bad_faces(recorded.meshes[static_cast<std::size_t>(i)], surface,
                   o.fold_repair.min_angle_deg, folded, slivers, &buffers);
    bad += static_cast<double>(folded.size() + slivers.size());
  };
  for (auto _ : state) {
    bad = 0;
    for (int i = 1; i <= 100; ++i) {
      state.PauseTiming();
      checks(i);
      state.ResumeTiming();
      checks(i);
    }
    benchmark::DoNotOptimize(bad);
  }
  state.counters["bad_faces"] = bad;
  state.counters["max_strain"] = strain;
}

BENCHMARK(BM_SafeguardChecks)->Unit(benchmark::kMicrosecond)->MinTime(1.0);

// The initial relaxation (AdaptOptions::initial_relaxation_rounds: smoothing, measuring and
// settling at the start time, so that sweeps there and back return to the first mesh) costs
// once, at initialisation, not per step. Twist at T = 0.008 initialised at t = 0, with the
// argument's number of rounds (0: none; 20: the default). Counter: the first mesh's triangles.
void BM_InitialRelaxation(benchmark::State& state) {
  AdaptOptions o = twist_options();
  o.initial_relaxation_rounds = static_cast<int>(state.range(0));
  double triangles = 0;
  for (auto _ : state) {
    state.PauseTiming();
    TwistRun run(o);
    state.ResumeTiming();
    run.adapter.initialize();
    triangles = static_cast<double>(run.adapter.mesh().n_faces());
  }
  state.counters["triangles"] = triangles;
}

BENCHMARK(BM_InitialRelaxation)->Arg(0)->Arg(20)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
}  // namespace dynamesh
