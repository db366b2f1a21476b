// Trilinear sampling of a volume at world points (for colouring a surface by MR intensity).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

class TrilinearSampler {
 public:
  TrilinearSampler() = default;
  // Keeps only the inverse of the grid's map (the volume is passed at each call, so the
  // owner of both can be moved freely).
  explicit TrilinearSampler(const VoxelGrid& grid) : to_voxel_(grid.linear.inverse()) {}

  // Points beyond the outermost voxel centres take the value at the nearest of them.
  double operator()(const ScalarVolume& volume, const Vec3& p) const {
    const auto& d = volume.grid.dims;
    const Vec3 u = to_voxel_ * (p - volume.grid.offset);
    int i0[3];
    double t[3];
    for (int a = 0; a < 3; ++a) {
      const double c = std::clamp(u[a], 0.0, static_cast<double>(d[a] - 1));
      i0[a] = std::min(static_cast<int>(c), std::max(d[a] - 2, 0));
      t[a] = d[a] > 1 ? c - i0[a] : 0.0;
    }
    const auto at = [&](int dx, int dy, int dz) -> double {
      return volume.at(std::min(i0[0] + dx, d[0] - 1), std::min(i0[1] + dy, d[1] - 1),
                       std::min(i0[2] + dz, d[2] - 1));
    };
    double result = 0.0;
    for (int c = 0; c < 8; ++c) {
      const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
      const double w = (dx ? t[0] : 1 - t[0]) * (dy ? t[1] : 1 - t[1]) * (dz ? t[2] : 1 - t[2]);
      result += w * at(dx, dy, dz);
    }
    return result;
  }

 private:
  Mat3 to_voxel_{Mat3::Identity()};
};

}  // namespace dynamesh
