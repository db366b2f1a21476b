#include "core/surface/volume/orthogonal_resampling.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/surface/volume/trilinear_sampler.h"

namespace dynamesh {
namespace {

constexpr double kCosineTolerance = 1e-4;

// Index-space position of every centre of `target` in `source`: c = A (i, j, k) + b.
void index_map(const VoxelGrid& source, const VoxelGrid& target, Mat3& a, Vec3& b) {
  const Mat3 inverse = source.linear.inverse();
  a = inverse * target.linear;
  b = inverse * (target.offset - source.offset);
}

bool inside(const VoxelGrid& g, const Vec3& c) {
  for (int axis = 0; axis < 3; ++axis)
    if (!(c[axis] >= -0.5 && c[axis] <= g.dims[axis] - 0.5)) return false;
  return true;
}

}  // namespace

bool has_orthogonal_axes(const VoxelGrid& grid) {
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const Vec3 u = grid.linear.col(a).normalized(), v = grid.linear.col(b).normalized();
      if (std::abs(u.dot(v)) > kCosineTolerance) return false;
    }
  return true;
}

VoxelGrid orthogonal_grid_around(const VoxelGrid& grid) {
  const double h = grid.spacing().minCoeff();
  const Box3 box = grid.world_bounds();
  VoxelGrid out;
  out.linear = Mat3::Identity() * h;
  out.offset = box.min + Vec3::Constant(0.5 * h);
  for (int axis = 0; axis < 3; ++axis)
    out.dims[axis] = std::max(1, static_cast<int>(std::ceil((box.max[axis] - box.min[axis]) / h)));
  return out;
}

ScalarVolume resampled(const ScalarVolume& volume, const VoxelGrid& target, float outside) {
  ScalarVolume out(target, outside);
  const TrilinearSampler sampler(volume.grid);
  Mat3 a;
  Vec3 b;
  index_map(volume.grid, target, a, b);
  const int nk = target.dims[2];
#pragma omp parallel for schedule(static)
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < target.dims[1]; ++j)
      for (int i = 0; i < target.dims[0]; ++i) {
        if (!inside(volume.grid, a * Vec3(i, j, k) + b)) continue;
        out.at(i, j, k) = static_cast<float>(sampler(volume, target.to_world(Vec3(i, j, k))));
      }
  return out;
}

MaskVolume resampled(const MaskVolume& mask, const VoxelGrid& target) {
  MaskVolume out(target, 0);
  Mat3 a;
  Vec3 b;
  index_map(mask.grid, target, a, b);
  const int nk = target.dims[2];
#pragma omp parallel for schedule(static)
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < target.dims[1]; ++j)
      for (int i = 0; i < target.dims[0]; ++i) {
        const Vec3 c = a * Vec3(i, j, k) + b;
        if (!inside(mask.grid, c)) continue;
        out.at(i, j, k) =
            mask.at(std::clamp(static_cast<int>(std::lround(c[0])), 0, mask.grid.dims[0] - 1),
                    std::clamp(static_cast<int>(std::lround(c[1])), 0, mask.grid.dims[1] - 1),
                    std::clamp(static_cast<int>(std::lround(c[2])), 0, mask.grid.dims[2] - 1));
      }
  return out;
}

}  // namespace dynamesh
