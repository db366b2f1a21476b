// VolumeImage: the read-only picture of a scan that renderers and pickers see besides the
// mesh — the intensities with their placement in the world (sform/qform, voxel_grid.h), the
// display window, and optionally an anatomical label atlas in the same world space. Shared
// (immutable, by shared_ptr) from the surface into every snapshot, so the renderer uploads
// it once as a 3-D texture and samples it per fragment (issue 14) instead of interpolating
// per-vertex colours across triangles millimetres wide.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

// A label volume (one region index per voxel, 0 = no region) with the regions' names, e.g.
// AAL on Colin27 (mricron's aal.nii.gz with its sidecar aal.nii.txt).
struct LabelAtlas {
  VoxelVolume<std::int32_t> labels;
  std::map<int, std::string> names;  // index -> name; a missing index reads "region N"
  std::string source;                // the file it came from

  // The region of the voxel nearest to world point p (nearest-neighbour: labels are
  // categories and must not be blended); 0 outside the volume.
  int label_at(const Vec3& p) const {
    const Vec3 u = labels.grid.to_voxel(p);
    const int i = static_cast<int>(std::lround(u.x())), j = static_cast<int>(std::lround(u.y())),
              k = static_cast<int>(std::lround(u.z()));
    return labels.grid.contains(i, j, k) ? labels.at(i, j, k) : 0;
  }
  std::string name_of(int label) const {
    if (label == 0) return "(none)";
    const auto it = names.find(label);
    return it != names.end() ? it->second : "region " + std::to_string(label);
  }
};

struct VolumeImage {
  std::shared_ptr<const ScalarVolume> intensity;  // world placement in intensity->grid
  // Robust display window [low, high]: the 1st and 99th percentiles inside the brain mask,
  // so that grey values stay put from frame to frame and layer to layer.
  Vec2 window{Vec2(0.0, 1.0)};
  std::shared_ptr<const LabelAtlas> atlas;  // null: no atlas loaded
};

}  // namespace dynamesh
