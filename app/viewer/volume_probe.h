// "What is here?" (issue 14): what the scan says at one world point — its voxel, the MR
// intensity (trilinear, as the layer is coloured), the atlas region (nearest voxel, as the
// region colours) — and the depth of the layer it lies on.
#pragma once

#include <array>
#include <string>

#include "core/surface/volume/volume_image.h"

namespace dynamesh {

struct VolumeProbe {
  Vec3 position{Vec3::Zero()};        // world mm
  Vec3 voxel{Vec3::Zero()};           // continuous voxel coordinates (centres at integers)
  std::array<int, 3> index{0, 0, 0};  // the nearest voxel
  bool inside = false;                // that voxel lies in the volume
  double intensity = 0.0;
  int region = 0;  // 0: none (or no atlas)
  std::string region_name;
  double depth = 0.0;  // mm below the brain's surface (the layer's depth)
};

VolumeProbe probe_volume(const VolumeImage& image, const Vec3& position, double depth);

}  // namespace dynamesh
