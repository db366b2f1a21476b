// Cost of a topology event (issue 16): the step in which F's zero set merges or splits against
// an ordinary step of the same run, on the blobs scene (merge at t = 0.1515, step 7 of 40) and
// the torus pinch (split at t = 0.5, step 20 of 40). Argument 1: 0 an ordinary step (blobs
// step 4, torus step 18), 1 the event step repaired locally (local_repair.h), 2 the event step
// with the global re-base (AdaptOptions::local_topology_repair = false, the engine before the
// local repair), 3 the step after the event (local repair). The run up to the measured step
// is not timed. Counters: vertices kept through the step (fraction), triangles after it.
#include <benchmark/benchmark.h>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

std::unique_ptr<Surface> make_example(int which) {
  if (which == 0) return make_scene("blobs");
  return make_scene(
      "expr", {},
      {{"implicit", "(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09 + 0.18*t*exp(-((x-1)^2+y^2+z^2)/0.16)"},
       {"bounds", "-1.5,-1.5,-0.5,1.5,1.5,0.5"}});
}

void BM_TopologyEventStep(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const int kind = static_cast<int>(state.range(1));
  constexpr int kSteps = 40;
  const int event_step = which == 0 ? 7 : 20;
  // kind 0: an ordinary step; 1: the event step, repaired locally; 2: the same with the global
  // re-base; 3: the step after the event (local repair), where the new neck or tips still move
  // fast (issue 16: 26.7x an ordinary step after the torus pinch, 32 sub-steps).
  const int measured = kind == 0 ? (which == 0 ? 4 : 18) : kind == 3 ? event_step + 1 : event_step;
  AdaptOptions o;
  o.local_topology_repair = kind != 2;
  double kept = 0, triangles = 0, runs = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto surface = make_example(which);
    const std::string name = which == 0 ? "blobs" : "expr";
    Adapter adapter(*surface, o, default_criteria(name, 0.0, o, 0.0));
    adapter.initialize();
    for (int i = 1; i < measured; ++i) adapter.step(static_cast<double>(i) / kSteps);
    state.ResumeTiming();
    const StepStats& s = adapter.step(static_cast<double>(measured) / kSteps);
    state.PauseTiming();
    kept += s.kept_fraction;
    triangles += static_cast<double>(s.triangles);
    ++runs;
    state.ResumeTiming();
  }
  state.counters["kept_fraction"] = kept / runs;
  state.counters["triangles"] = triangles / runs;
}

BENCHMARK(BM_TopologyEventStep)
    ->ArgsProduct({{0, 1}, {0, 1, 2, 3}})
    ->ArgNames({"torus", "kind"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
}  // namespace dynamesh
