// Cost of the tangential correction (Equation 1) against the whole step, per scene. Goal
// (issue 5): under a third of the step. Counters: smooth_fraction = smoothing seconds over
// step seconds, triangles.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

void BM_StepWithSmoothing(benchmark::State& state, const std::string& scene) {
  auto surface = make_scene(scene);
  AdaptOptions o;
  double L = 0;
  for (const SurfaceParameter& p : surface->parameters())
    if (p.name == "L") L = p.value;
  Adapter adapter(*surface, o, default_criteria(scene, L, o, 0.0));
  adapter.initialize();
  const double end = scene == "sphere" ? 0.5 : 1.0;
  int i = 0;
  double smooth = 0, total = 0;
  for (auto _ : state) {
    // Forth and back over the animation in 50-step strides, so every iteration deforms.
    const int k = i++ % 100;
    const StepStats& s = adapter.step(end * (k < 50 ? k + 1 : 99 - k) / 50.0);
    smooth += s.seconds.smooth;
    total += s.seconds.total;
    benchmark::DoNotOptimize(s.triangles);
  }
  state.counters["smooth_fraction"] = total > 0 ? smooth / total : 0.0;
  state.counters["triangles"] = static_cast<double>(adapter.mesh().n_faces());
}

BENCHMARK_CAPTURE(BM_StepWithSmoothing, sphere, std::string("sphere"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepWithSmoothing, capsule_bend, std::string("capsule-bend"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepWithSmoothing, sinc, std::string("sinc"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepWithSmoothing, twist, std::string("twist"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dynamesh
