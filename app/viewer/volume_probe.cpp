#include "app/viewer/volume_probe.h"

#include <cmath>

#include "core/surface/volume/trilinear_sampler.h"

namespace dynamesh {

VolumeProbe probe_volume(const VolumeImage& image, const Vec3& position, double depth) {
  VolumeProbe p;
  p.position = position;
  p.depth = depth;
  if (!image.intensity) return p;
  const ScalarVolume& v = *image.intensity;
  p.voxel = v.grid.to_voxel(position);
  for (int a = 0; a < 3; ++a) p.index[a] = static_cast<int>(std::lround(p.voxel[a]));
  p.inside = v.grid.contains(p.index[0], p.index[1], p.index[2]);
  p.intensity = TrilinearSampler(v.grid)(v, position);
  if (image.atlas) {
    p.region = image.atlas->label_at(position);
    p.region_name = image.atlas->name_of(p.region);
  }
  return p;
}

}  // namespace dynamesh
