// libFuzzer target: the NIfTI-1 reader (core/io/nifti_volume.h) on arbitrary bytes, plain or
// gzip (chosen by the gzip magic, as a user's file name would say). Any outcome but a
// returned volume or a std::runtime_error is a bug: a crash, a sanitizer report, a hang
// (libFuzzer's -timeout) or an allocation beyond -rss_limit_mb.
#include <cmath>
#include <stdexcept>

#include "core/io/nifti_volume.h"
#include "fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  const std::string path = dynamesh::fuzz::input_file(data, size, gz ? ".nii.gz" : ".nii");
  try {
    const dynamesh::NiftiVolume v = dynamesh::read_nifti_volume(path);
    // What the reader promises: a finite placement with sane voxels, finite values.
    if (!v.volume.grid.linear.allFinite()) __builtin_trap();
    for (float x : v.volume.values)
      if (!std::isfinite(x)) __builtin_trap();
  } catch (const std::runtime_error&) {
  }
  return 0;
}
