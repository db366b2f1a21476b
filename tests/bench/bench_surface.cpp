// Surface evaluation throughput per scene: value + gradient (what sampling and projection
// cost), Hessian (curvature) and full Newton projection, on one thread and on all threads
// (argument 0 = omp_get_max_threads()). DESIGN.md's speed yardstick is this pure evaluation
// cost at every sample and vertex.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/surface/projection.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

constexpr int kPoints = 1 << 16;

int thread_count(const benchmark::State& state) {
  return state.range(0) == 0 ? omp_get_max_threads() : static_cast<int>(state.range(0));
}

// Points near the surface at t = 0.5: bounding-box points pulled halfway onto the surface
// (implicit), or random parameters (parametric).
struct Workload {
  std::unique_ptr<Surface> scene;
  std::vector<Vec3> points;
  std::vector<Vec2> uvs;
};

const Workload& workload(const std::string& name) {
  static std::map<std::string, Workload> cache;
  auto [it, fresh] = cache.try_emplace(name);
  if (!fresh) return it->second;
  Workload& w = it->second;
  w.scene = make_scene(name);
  w.scene->set_time(0.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Box3 box = w.scene->bounds();
  if (auto* implicit = dynamic_cast<const ImplicitSurface*>(w.scene.get())) {
    while (static_cast<int>(w.points.size()) < kPoints) {
      const Vec3 p = box.min + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(box.size());
      const ProjectionResult r = project_to_surface(*implicit, p);
      if (r.converged) w.points.push_back(0.5 * (p + r.point));
    }
  } else {
    for (int i = 0; i < kPoints; ++i) w.uvs.emplace_back(2 * unit(rng) - 1, 2 * unit(rng) - 1);
  }
  return w;
}

void report(benchmark::State& state, int threads) {
  state.SetItemsProcessed(state.iterations() * kPoints);
  state.counters["threads"] = threads;
}

void BM_ValueGradient(benchmark::State& state, const std::string& name) {
  const Workload& w = workload(name);
  const int threads = thread_count(state);
  for (auto _ : state) {
    double sum = 0;
    if (auto* s = dynamic_cast<const ImplicitSurface*>(w.scene.get())) {
#pragma omp parallel for num_threads(threads) reduction(+ : sum) schedule(static)
      for (int i = 0; i < kPoints; ++i) {
        Vec3 g;
        sum += s->value_gradient(w.points[i], g) + g.x();
      }
    } else {
      // Parametric: the position and its first and second derivatives in one call.
      auto* p = static_cast<const ParametricSurface*>(w.scene.get());
#pragma omp parallel for num_threads(threads) reduction(+ : sum) schedule(static)
      for (int i = 0; i < kPoints; ++i) {
        const ParametricDerivatives d = p->derivatives(w.uvs[i]);
        sum += d.s.y() + d.su.y();
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  report(state, threads);
}

void BM_Hessian(benchmark::State& state, const std::string& name) {
  const Workload& w = workload(name);
  const auto* s = dynamic_cast<const ImplicitSurface*>(w.scene.get());
  const int threads = thread_count(state);
  for (auto _ : state) {
    double sum = 0;
#pragma omp parallel for num_threads(threads) reduction(+ : sum) schedule(static)
    for (int i = 0; i < kPoints; ++i) sum += s->hessian(w.points[i]).trace();
    benchmark::DoNotOptimize(sum);
  }
  report(state, threads);
}

void BM_Projection(benchmark::State& state, const std::string& name) {
  const Workload& w = workload(name);
  const auto* s = dynamic_cast<const ImplicitSurface*>(w.scene.get());
  const int threads = thread_count(state);
  for (auto _ : state) {
    double sum = 0;
#pragma omp parallel for num_threads(threads) reduction(+ : sum) schedule(static)
    for (int i = 0; i < kPoints; ++i) sum += project_to_surface(*s, w.points[i]).point.x();
    benchmark::DoNotOptimize(sum);
  }
  report(state, threads);
}

void register_all() {
  for (const char* name : {"sphere", "capsule-bend", "sinc", "twist"}) {
    const std::string n = name;
    benchmark::RegisterBenchmark(("ValueGradient/" + n).c_str(), BM_ValueGradient, n)
        ->Arg(1)
        ->Arg(0)
        ->UseRealTime();
    if (n == "sinc") continue;
    benchmark::RegisterBenchmark(("Hessian/" + n).c_str(), BM_Hessian, n)
        ->Arg(1)
        ->Arg(0)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("Projection/" + n).c_str(), BM_Projection, n)
        ->Arg(1)
        ->Arg(0)
        ->UseRealTime();
  }
}

const int kRegistered = (register_all(), 0);

}  // namespace
}  // namespace dynamesh
