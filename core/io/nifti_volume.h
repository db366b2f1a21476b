// Reading NIfTI-1 volumes (.nii, .nii.gz) into a ScalarVolume in world millimetres.
//
// nifticlib provides the pieces (znzlib streams for plain and gzip files, header byte
// swapping, the quaternion-to-matrix map, datatype names), while the validation and the
// reading of the voxels are done here: nifticlib's own nifti_image_read reports problems only
// on stderr and returns NULL, and silently zeroes NaNs; here every malformed, truncated or
// unsupported input ends in one std::runtime_error that names the file and the problem.
// Voxels are converted to float with the header's scl_slope / scl_inter applied.
//
// Placement follows the NIfTI-1 rules (nifti1.h, "METHOD 3 / 2 / 1"): the sform when
// sform_code > 0, else the qform when qform_code > 0, else a diagonal map from pixdim.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

enum class VoxelPlacement { kSform, kQform, kPixdim };

struct NiftiVolume {
  ScalarVolume volume;  // first 3-D volume, intensities after scaling
  int datatype = 0;     // NIfTI datatype code of the stored voxels
  std::string datatype_name;
  double scl_slope = 1.0, scl_inter = 0.0;  // as applied (slope 0 in the file means 1, 0)
  VoxelPlacement placement = VoxelPlacement::kPixdim;
  int volumes_in_file = 1;     // product of dims 4..7; only the first volume is read
  std::size_t non_finite = 0;  // NaN / infinite values (after scaling), replaced by 0
};

// Throws std::runtime_error naming `path` and what is wrong: missing or unreadable file,
// file name without .nii / .nii.gz, not NIfTI-1 (wrong header size or magic, NIfTI-2,
// a .hdr/.img pair), bad dimensions, unsupported datatype (complex, RGB, binary, ...),
// truncated data, singular or non-finite voxel-to-world map.
// `progress`, when set, is called with the fraction of voxel bytes read so far.
NiftiVolume read_nifti_volume(const std::filesystem::path& path,
                              const std::function<void(double)>& progress = {});

}  // namespace dynamesh
