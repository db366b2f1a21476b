// Face-connected (6-neighbour) components of a binary mask: keeping the largest one and
// filling the holes of a solid.
#pragma once

#include <cstddef>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

// Clears every foreground voxel outside the largest 6-connected component. Returns the number
// of components found (0 for an empty mask).
std::size_t keep_largest_component(MaskVolume& mask);

// Sets every background voxel that is not 6-connected to the volume's border (cavities such
// as the ventricles' closed interior). Returns the number of voxels filled.
std::size_t fill_holes(MaskVolume& mask);

}  // namespace dynamesh
