// Volume pipeline speed on the default MR volume (Colin27, 181 x 217 x 181 voxels): reading,
// the whole preprocessing (goal: under 5 s on a 2-core machine), and evaluations of the
// layer function per second.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <random>
#include <vector>

#include "core/io/nifti_volume.h"
#include "core/surface/volume/mri_surface.h"

namespace dynamesh {
namespace {

bool have_colin(benchmark::State& state) {
  if (std::filesystem::exists(kDefaultMriVolume)) return true;
  state.SkipWithError("ch2bet.nii.gz not installed (Debian package mricron-data)");
  return false;
}

void BM_ReadNifti(benchmark::State& state) {
  if (!have_colin(state)) return;
  for (auto _ : state) benchmark::DoNotOptimize(read_nifti_volume(kDefaultMriVolume));
}
BENCHMARK(BM_ReadNifti)->Unit(benchmark::kMillisecond)->UseRealTime();

// Read + segment + distance transform + critical points, with the stage times as counters.
void BM_MriPreprocess(benchmark::State& state) {
  if (!have_colin(state)) return;
  MriTimings t;
  for (auto _ : state) {
    const auto surface = make_mri_surface();
    t = surface->layers().timings();
  }
  state.counters["read_s"] = t.read;
  state.counters["segment_s"] = t.segment;
  state.counters["distance_s"] = t.distance;
  state.counters["critical_points_s"] = t.critical_points;  // issue 16's search, once per load
}
BENCHMARK(BM_MriPreprocess)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// Points spread near the 15 mm layer, as an adapter would evaluate them.
const MriSurface& colin() {
  static const std::unique_ptr<MriSurface> surface = [] {
    auto s = make_mri_surface();
    s->set_time(1.0);
    return s;
  }();
  return *surface;
}

std::vector<Vec3> layer_points(const MriSurface& s, int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box3 b = s.bounds();
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    points.push_back(b.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(b.size()));
  }
  return points;
}

void BM_MriValueGradient(benchmark::State& state) {
  if (!have_colin(state)) return;
  const MriSurface& s = colin();
  const std::vector<Vec3> points = layer_points(s, 1 << 16);
  std::size_t i = 0;
  for (auto _ : state) {
    Vec3 g;
    benchmark::DoNotOptimize(s.value_gradient(points[i++ & (points.size() - 1)], g));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MriValueGradient);

void BM_MriHessian(benchmark::State& state) {
  if (!have_colin(state)) return;
  const MriSurface& s = colin();
  const std::vector<Vec3> points = layer_points(s, 1 << 16);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.hessian(points[i++ & (points.size() - 1)]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MriHessian);

}  // namespace
}  // namespace dynamesh
