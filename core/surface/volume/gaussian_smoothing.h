// Separable Gaussian smoothing of a volume with a width given in millimetres, so anisotropic
// voxels are smoothed by the same physical amount along every axis.
#pragma once

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

// Convolves with a Gaussian of standard deviation sigma_mm (truncated at 3 sigma, border
// voxels replicated). Axes whose sigma is below a tenth of a voxel are left alone; sigma_mm
// <= 0 returns a copy.
ScalarVolume gaussian_smoothed(const ScalarVolume& volume, double sigma_mm);
// The same in place (one scratch buffer instead of a copy and a scratch buffer).
void gaussian_smooth(ScalarVolume& volume, double sigma_mm);

}  // namespace dynamesh
