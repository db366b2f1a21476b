// The three orthogonal slices of the scan through the probed point (issue 14): the voxel
// planes i, j and k = the point's nearest voxel, in the display window, each with the
// current layer's intersection curve and the point marked. Clicking in a slice moves the
// point there (the slice's own index stays). ImGui window; the slices are GL textures
// rebuilt only when their plane, the scan or the window changes.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "app/viewer/widget_report.h"
#include "core/adapt/mesh_snapshot.h"
#include "core/surface/volume/volume_image.h"

namespace dynamesh {

class SlicePanel {
 public:
  SlicePanel() = default;
  ~SlicePanel();
  SlicePanel(const SlicePanel&) = delete;
  SlicePanel& operator=(const SlicePanel&) = delete;

  // Draws the window at (x, y) in window pixels, each slice at most `side` pixels wide.
  // Returns the new point when a slice was clicked. With `widgets`, each slice image's
  // rectangle is added as "slice_i", "slice_j", "slice_k" (the normal's voxel axis).
  std::optional<Vec3> draw(const VolumeImage& image, const Vec3& point,
                           const std::shared_ptr<const MeshSnapshot>& mesh, const Vec2& window,
                           float x, float y, float side, std::vector<WidgetRect>* widgets);

 private:
  struct Slice {
    unsigned texture = 0;
    int index = -1;
    std::shared_ptr<const ScalarVolume> volume;  // kept: never mistaken by its address
    Vec2 window{Vec2::Zero()};
  };
  void update_texture(Slice& slice, int axis, int index,
                      const std::shared_ptr<const ScalarVolume>& volume, const Vec2& window);
  // The snapshot's vertices in voxel coordinates (cached per snapshot).
  const std::vector<Vec3>& mesh_voxels(const std::shared_ptr<const MeshSnapshot>& mesh,
                                       const VoxelGrid& grid);

  std::array<Slice, 3> slices_;
  std::shared_ptr<const MeshSnapshot> voxels_of_;
  std::vector<Vec3> voxels_;
};

// The two in-plane voxel axes of the slice normal to `axis`: across, then up.
std::array<int, 2> slice_axes(int axis);

}  // namespace dynamesh
