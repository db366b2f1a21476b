// The mri scene's preparation, stage by stage, on Colin27 (181 x 217 x 181 voxels of 1 mm,
// mricron-data): the issue-14 goal is a closed clean layer within 10 s of starting, the
// preparation being most of it. Each stage runs on the same input as in MriLayers (the
// default MriLayersOptions); "Time" is wall clock, "CPU" the whole process's CPU time (all
// OpenMP threads), which a loaded machine inflates far less than the wall clock. Run with
//   dynamesh_bench --benchmark_filter=MriPrep
#include <benchmark/benchmark.h>

#include <filesystem>

#include "core/io/nifti_volume.h"
#include "core/surface/volume/brain_extraction.h"
#include "core/surface/volume/connected_components.h"
#include "core/surface/volume/distance_transform.h"
#include "core/surface/volume/gaussian_smoothing.h"
#include "core/surface/volume/mri_layers.h"
#include "core/surface/volume/otsu_threshold.h"
#include "core/surface/volume/segmentation.h"

namespace dynamesh {
namespace {

const std::filesystem::path kHead = "/usr/share/mricron/templates/ch2.nii.gz";

bool have(benchmark::State& state, const std::filesystem::path& path) {
  if (std::filesystem::exists(path)) return true;
  state.SkipWithError("Colin27 not installed (Debian package mricron-data)");
  return false;
}

// The inputs of every stage, computed once with the default options.
struct Stages {
  MriLayersOptions options;
  ScalarVolume intensity, smoothed;
  MaskVolume thresholded, opened, head_opened, closed;
  ScalarVolume indicator, distance;
};

MaskVolume above(const ScalarVolume& v, double threshold) {
  MaskVolume m(v.grid, 0);
  for (std::size_t i = 0; i < v.values.size(); ++i) m.values[i] = v.values[i] > threshold;
  return m;
}

const Stages& stages() {
  static const Stages s = [] {
    Stages s;
    const SegmentationOptions& o = s.options.segmentation;
    s.intensity = read_nifti_volume(kDefaultMriVolume).volume;
    s.smoothed = gaussian_smoothed(s.intensity, o.smoothing_sigma_mm);
    s.thresholded = above(s.smoothed, otsu_threshold(s.smoothed.values));
    s.opened = s.thresholded;
    open_mask(s.opened, o.opening_radius_mm);
    keep_largest_component(s.opened);
    s.closed = s.opened;
    close_mask(s.closed, o.closing_radius_mm);
    fill_holes(s.closed);
    s.indicator = ScalarVolume(s.closed.grid, 0.0f);
    for (std::size_t i = 0; i < s.closed.values.size(); ++i)
      s.indicator.values[i] = s.closed.values[i];
    s.indicator = gaussian_smoothed(s.indicator, s.options.boundary_smoothing_mm);
    s.distance = signed_distance_to_level(s.indicator, 0.5);
    if (std::filesystem::exists(kHead)) {
      const ScalarVolume head = gaussian_smoothed(read_nifti_volume(kHead).volume, 1.0);
      s.head_opened = above(head, otsu_threshold(head.values));
      open_mask(s.head_opened, o.opening_radius_mm);
      keep_largest_component(s.head_opened);
    }
    return s;
  }();
  return s;
}

#define MRI_PREP_BENCHMARK(name) \
  BENCHMARK(name)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()

void BM_MriPrepRead(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  for (auto _ : state) benchmark::DoNotOptimize(read_nifti_volume(kDefaultMriVolume));
}
MRI_PREP_BENCHMARK(BM_MriPrepRead);

void BM_MriPrepSmoothIntensity(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        gaussian_smoothed(s.intensity, s.options.segmentation.smoothing_sigma_mm));
}
MRI_PREP_BENCHMARK(BM_MriPrepSmoothIntensity);

void BM_MriPrepOpening(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) {
    MaskVolume m = s.thresholded;
    open_mask(m, s.options.segmentation.opening_radius_mm);
    benchmark::DoNotOptimize(m.values.data());
  }
}
MRI_PREP_BENCHMARK(BM_MriPrepOpening);

void BM_MriPrepLargestComponent(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) {
    MaskVolume m = s.thresholded;
    benchmark::DoNotOptimize(keep_largest_component(m));
  }
}
MRI_PREP_BENCHMARK(BM_MriPrepLargestComponent);

// Colin27 with its skull: the opened head mask, eroded by 8 mm, split, dilated back.
void BM_MriPrepBrainExtraction(benchmark::State& state) {
  if (!have(state, kHead)) return;
  const Stages& s = stages();
  for (auto _ : state)
    benchmark::DoNotOptimize(extract_brain(s.head_opened, s.options.segmentation.extraction));
}
MRI_PREP_BENCHMARK(BM_MriPrepBrainExtraction);

void BM_MriPrepClosing(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) {
    MaskVolume m = s.opened;
    close_mask(m, s.options.segmentation.closing_radius_mm);
    benchmark::DoNotOptimize(m.values.data());
  }
}
MRI_PREP_BENCHMARK(BM_MriPrepClosing);

void BM_MriPrepFillHoles(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) {
    MaskVolume m = s.closed;
    benchmark::DoNotOptimize(fill_holes(m));
  }
}
MRI_PREP_BENCHMARK(BM_MriPrepFillHoles);

void BM_MriPrepBoundaryBlur(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) {
    ScalarVolume indicator(s.closed.grid, 0.0f);
    for (std::size_t i = 0; i < s.closed.values.size(); ++i)
      indicator.values[i] = s.closed.values[i];
    benchmark::DoNotOptimize(gaussian_smoothed(indicator, s.options.boundary_smoothing_mm));
  }
}
MRI_PREP_BENCHMARK(BM_MriPrepBoundaryBlur);

void BM_MriPrepLevelDistance(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state) benchmark::DoNotOptimize(signed_distance_to_level(s.indicator, 0.5));
}
MRI_PREP_BENCHMARK(BM_MriPrepLevelDistance);

void BM_MriPrepDistanceBlur(benchmark::State& state) {
  if (!have(state, kDefaultMriVolume)) return;
  const Stages& s = stages();
  for (auto _ : state)
    benchmark::DoNotOptimize(gaussian_smoothed(s.distance, s.options.distance_smoothing_mm));
}
MRI_PREP_BENCHMARK(BM_MriPrepDistanceBlur);

// The whole preparation (MriLayers::build): skull-stripped Colin27 and the head with skull.
void BM_MriPrepWhole(benchmark::State& state, const std::filesystem::path& volume) {
  if (!have(state, volume)) return;
  MriLayersOptions options;
  options.volume_path = volume;
  for (auto _ : state) benchmark::DoNotOptimize(MriLayers::build(options).max_depth());
}
BENCHMARK_CAPTURE(BM_MriPrepWhole, brain, std::filesystem::path(kDefaultMriVolume))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_MriPrepWhole, head, kHead)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(2);

}  // namespace
}  // namespace dynamesh
