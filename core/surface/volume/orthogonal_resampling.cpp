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

// Calls visit(i, j, k, c) for every voxel (i, j, k) of `target` whose centre lies inside
// `source`, c being that centre in `source`'s index space: the grid walk both resamplers
// share (they differ only in how they read the source there).
template <class Visit>
void for_each_covered_voxel(const VoxelGrid& source, const VoxelGrid& target, Visit&& visit) {
  Mat3 a;
  Vec3 b;
  index_map(source, target, a, b);
  const int nk = target.dims[2];
#pragma omp parallel for schedule(static)
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < target.dims[1]; ++j)
      for (int i = 0; i < target.dims[0]; ++i) {
        const Vec3 c = a * Vec3(i, j, k) + b;
        if (inside(source, c)) visit(i, j, k, c);
      }
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
  for_each_covered_voxel(volume.grid, target, [&](int i, int j, int k, const Vec3&) {
    out.at(i, j, k) = static_cast<float>(sampler(volume, target.to_world(Vec3(i, j, k))));
  });
  return out;
}

MaskVolume resampled(const MaskVolume& mask, const VoxelGrid& target) {
  MaskVolume out(target, 0);
  const auto nearest = [&](const Vec3& c, int axis) {
    return std::clamp(static_cast<int>(std::lround(c[axis])), 0, mask.grid.dims[axis] - 1);
  };
  for_each_covered_voxel(mask.grid, target, [&](int i, int j, int k, const Vec3& c) {
    out.at(i, j, k) = mask.at(nearest(c, 0), nearest(c, 1), nearest(c, 2));
  });
  return out;
}

}  // namespace dynamesh
