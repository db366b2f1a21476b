// Exact Euclidean distance transforms of binary masks in millimetres, honouring anisotropic
// voxel spacing, and the signed distance to a mask's boundary.
//
// The transform is the separable algorithm of P. Felzenszwalb and D. Huttenlocher,
// "Distance Transforms of Sampled Functions", Theory of Computing 8 (2012): one pass per
// axis, each the lower envelope of parabolas h^2 (q - p)^2 + f(p) along a line, linear in the
// number of voxels. Each pass also carries the index of the voxel that attains the minimum
// (the feature transform), which the signed distance uses.
#pragma once

#include <cstdint>
#include <vector>

#include "core/surface/volume/progress.h"
#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

struct DistanceTransformResult {
  std::vector<float> squared;          // mm^2 to the nearest target voxel centre (+inf: none)
  std::vector<std::uint32_t> nearest;  // index of that voxel (UINT32_MAX: none)
};

// For every voxel, the exact squared Euclidean distance (with spacing h_i = |column i| of
// the grid's linear map, i.e. exact for any rotated or axis-aligned grid) to the nearest
// voxel whose mask value equals `target`, and that voxel. Runs in parallel (OpenMP);
// `progress` gets the fraction of passes done under `stage`.
DistanceTransformResult distance_transform(const MaskVolume& mask, std::uint8_t target,
                                           const ProgressCallback& progress = {},
                                           std::string_view stage = "distance transform");

// The squared distances alone (no feature transform), written into `squared`, which is
// resized to the grid: callers that threshold several transforms (morphology) reuse one
// buffer instead of faulting in two fresh full-grid arrays per transform.
void squared_distance_transform(const MaskVolume& mask, std::uint8_t target,
                                std::vector<float>& squared);

// Signed distance to the mask's boundary at every voxel centre, in mm: negative inside.
// The boundary is taken as the faces of the mask's voxel cells: from a voxel x whose nearest
// voxel of the other kind is f, the distance is |x - f| less the part of the segment that
// lies inside f's cell, so neighbours across a face get -h/2 and +h/2 and the zero level
// passes through the face. Throws std::invalid_argument for an empty or full mask.
ScalarVolume signed_distance(const MaskVolume& mask, const ProgressCallback& progress = {});

// Signed distance in mm (negative inside, where field > level) to the level set
// {field = level} of a smooth field, e.g. a Gaussian-smoothed mask, with sub-voxel accuracy:
// every voxel that has a face neighbour across the level set gets its nearest point on it by
// one Newton step, c = x - (f - level) grad f / |grad f|^2 (central differences, chain rule
// through the grid's map); the feature transform of those voxels then gives every voxel q
// its nearest such voxel v, and D(q) = +-|q - c_v|; within 4 voxels of the level set the
// foot points of v's 26 neighbours are tried too and the distance is taken to the best one's
// tangent plane (exact to first order). Unlike the binary transform, the zero
// level follows the smooth level set instead of the voxel staircase, so second derivatives
// (curvature) of the interpolated D are meaningful. Throws std::invalid_argument when no
// voxel pair straddles the level.
ScalarVolume signed_distance_to_level(const ScalarVolume& field, double level,
                                      const ProgressCallback& progress = {});

}  // namespace dynamesh
