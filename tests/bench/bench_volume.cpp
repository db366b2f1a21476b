// Volume pipeline speed: reading the default MR volume.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "core/io/nifti_volume.h"

namespace dynamesh {
namespace {

const char* const kColin = "/usr/share/mricron/templates/ch2bet.nii.gz";

void BM_ReadNifti(benchmark::State& state) {
  if (!std::filesystem::exists(kColin)) {
    state.SkipWithError("ch2bet.nii.gz not installed (Debian package mricron-data)");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(read_nifti_volume(kColin));
}
BENCHMARK(BM_ReadNifti)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dynamesh
