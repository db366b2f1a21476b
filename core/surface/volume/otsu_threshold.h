// Otsu's threshold (N. Otsu, "A threshold selection method from gray-level histograms",
// IEEE Trans. SMC 9(1), 1979): the intensity that maximises the between-class variance of
// the two classes it separates.
#pragma once

#include <vector>

namespace dynamesh {

// Over a histogram of `bins` equal bins spanning [min, max] of `values`; returns the upper
// edge of the last bin of the lower class (a voxel is foreground when value > threshold).
// Constant input returns that constant.
double otsu_threshold(const std::vector<float>& values, int bins = 256);

}  // namespace dynamesh
