// Adapting the mri scene on Colin27: the initial refinement of the surface layer and the
// per-step cost while the depth sweeps 0 -> 15 mm -> 0 at 1 mm per step, at the scene's
// suggested T = 0.5 mm (eps = T/4) and density. Preprocessing is in bench_volume.cpp.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "core/surface/volume/mri_layers.h"
#include "core/surface/volume/mri_scene.h"

namespace dynamesh {
namespace {

constexpr int kStepsPerSweep = 15;  // depth_max = 15 mm: 1 mm per step

AdaptOptions suggested_options() {
  AdaptOptions o;
  o.threshold = kMriSuggestions.threshold;
  o.epsilon = o.threshold / 4;
  o.density = kMriSuggestions.density;
  return o;
}

void BM_MriAdaptInitialize(benchmark::State& state) {
  if (!std::filesystem::exists(kDefaultMriVolume)) {
    state.SkipWithError("ch2bet.nii.gz not installed (Debian package mricron-data)");
    return;
  }
  const auto surface = make_scene("mri");
  const AdaptOptions o = suggested_options();
  StepStats stats;
  for (auto _ : state) {
    Adapter adapter(*surface, o, default_criteria("mri", 0.0, o, 0.0));
    stats = adapter.initialize();
  }
  state.counters["triangles"] = static_cast<double>(stats.triangles);
  state.counters["samples"] = static_cast<double>(stats.samples);
}
BENCHMARK(BM_MriAdaptInitialize)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// One iteration = one step; the depth goes down and up again (30 iterations: one sweep
// 0 -> 15 -> 0 mm). Counters: mean triangles, splits and welds per step, the phases' mean
// times, and the triangle counts at the start and after the last step.
void BM_MriAdaptStep(benchmark::State& state) {
  if (!std::filesystem::exists(kDefaultMriVolume)) {
    state.SkipWithError("ch2bet.nii.gz not installed (Debian package mricron-data)");
    return;
  }
  const auto surface = make_scene("mri");
  const AdaptOptions o = suggested_options();
  Adapter adapter(*surface, o, default_criteria("mri", 0.0, o, 0.0));
  const double initial_triangles = static_cast<double>(adapter.initialize().triangles);
  int i = 0;
  double triangles = 0, splits = 0, welds = 0;
  PhaseSeconds sum;
  for (auto _ : state) {
    ++i;
    const int k = i % (2 * kStepsPerSweep);
    const double t = (k <= kStepsPerSweep ? k : 2 * kStepsPerSweep - k) / double(kStepsPerSweep);
    const StepStats& s = adapter.step(t);
    triangles += static_cast<double>(s.triangles);
    splits += static_cast<double>(s.splits);
    welds += static_cast<double>(s.welds);
    sum.project += s.seconds.project;
    sum.smooth += s.seconds.smooth;
    sum.sample += s.seconds.sample;
    sum.weld += s.seconds.weld;
    sum.split += s.seconds.split;
  }
  const double n = std::max(1, i);
  state.counters["triangles"] = triangles / n;
  // After one full sweep (30 iterations) the depth is back at 0: a mesh that returned to
  // its start has about the initial count.
  state.counters["triangles_initial"] = initial_triangles;
  state.counters["triangles_last"] = static_cast<double>(adapter.mesh().n_faces());
  state.counters["splits"] = splits / n;
  state.counters["welds"] = welds / n;
  state.counters["project_ms"] = 1e3 * sum.project / n;
  state.counters["smooth_ms"] = 1e3 * sum.smooth / n;
  state.counters["sample_ms"] = 1e3 * sum.sample / n;
  state.counters["weld_ms"] = 1e3 * sum.weld / n;
  state.counters["split_ms"] = 1e3 * sum.split / n;
}
BENCHMARK(BM_MriAdaptStep)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);

}  // namespace
}  // namespace dynamesh
