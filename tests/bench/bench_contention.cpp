// A step on a busy machine (issue 17): the median step with one competing busy thread
// against the median quiet step, same scene, same process. Goal: busy <= 2x quiet.
// The engine starts OpenMP with a passive wait policy (core/parallel.h); run this binary
// with OMP_WAIT_POLICY=active to see the spinning default it replaces. The `policy` label
// says which one ran.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/parallel.h"
#include "core/surface/scene_registry.h"
#include "median.h"

namespace dynamesh {
namespace {

// A thread that keeps one core busy until destroyed (what a renderer or a build does).
class BusyThread {
 public:
  BusyThread()
      : thread_([this] {
          volatile double x = 1.0;
          while (!stop_.load(std::memory_order_relaxed)) x = x * 1.0000001 + 1e-9;
        }) {}
  ~BusyThread() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Steps t by 1e-3 around 0.5 with and without a busy thread, alternating blocks of steps
// so that both see the same drift of the machine's other load.
void BM_StepUnderContention(benchmark::State& state, const std::string& name, double threshold) {
  auto surface = make_scene(name);
  surface->set_time(0.5);
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  double edge_length = 0.0;  // the sphere's multi-criteria half needs its L
  for (const SurfaceParameter& p : surface->parameters())
    if (p.name == "L") edge_length = p.value;
  Adapter adapter(*surface, o, default_criteria(name, edge_length, o, 0.0));
  adapter.initialize();
  double t = 0.5;
  std::vector<double> quiet, busy;
  for (auto _ : state) {
    for (int k = 0; k < 5; ++k) quiet.push_back(adapter.step(t += 1e-3).seconds.total);
    BusyThread competitor;
    for (int k = 0; k < 5; ++k) busy.push_back(adapter.step(t += 1e-3).seconds.total);
  }
  state.SetLabel(engine_wait_policy());
  state.counters["triangles"] = static_cast<double>(adapter.mesh().n_faces());
  state.counters["quiet_ms"] = 1e3 * median(quiet);
  state.counters["busy_ms"] = 1e3 * median(busy);
  state.counters["busy_over_quiet"] = median(busy) / median(quiet);
}

BENCHMARK_CAPTURE(BM_StepUnderContention, sphere_T9e - 4, std::string("sphere"), 9e-4)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(6);
BENCHMARK_CAPTURE(BM_StepUnderContention, twist_T1e - 3, std::string("twist"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4);
BENCHMARK_CAPTURE(BM_StepUnderContention, capsule_T1e - 3, std::string("capsule-bend"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4);

}  // namespace
}  // namespace dynamesh
