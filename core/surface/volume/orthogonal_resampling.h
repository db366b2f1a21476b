// Resampling a volume whose voxel axes are not perpendicular (a sheared sform or qform)
// onto a grid whose axes are: the distance transforms (distance_transform.h) take the
// spacing along each index axis as the whole metric, which is exact for any rotated grid
// but not for a sheared one, where distances come out wrong by up to the cosine between
// the axes (a shear of 0.5 tilts an axis by 27 degrees) and D is then no distance.
#pragma once

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

// Whether the grid's voxel axes are perpendicular (|cos| of every pair below 1e-4).
bool has_orthogonal_axes(const VoxelGrid& grid);

// The world-axis-aligned grid with cubic voxels of the smallest spacing of `grid` covering
// its voxels' world box.
VoxelGrid orthogonal_grid_around(const VoxelGrid& grid);

// `volume` sampled at the centres of `target` (trilinear; points outside the volume take
// `outside`).
ScalarVolume resampled(const ScalarVolume& volume, const VoxelGrid& target, float outside);
// The same for a mask (nearest voxel).
MaskVolume resampled(const MaskVolume& mask, const VoxelGrid& target);

}  // namespace dynamesh
