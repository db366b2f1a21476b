// A VolumeImage on the GPU: the intensities as a 3-D float texture (linear filtering: the
// trilinear interpolation between voxel centres that TrilinearSampler does on the CPU) and
// the label atlas as a 3-D integer texture (read with texelFetch at the nearest voxel).
// Uploaded once per scan (the snapshots share one VolumeImage), never per frame, and only
// when a frame first samples it: the labels (as large as the scan) wait for the region
// colours, and neither delays the first frame of a shaded layer. GL 3.3 core, so it works on
// OSMesa's llvmpipe as in the window.
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "core/surface/volume/volume_image.h"

namespace dynamesh {

class VolumeTextures {
 public:
  VolumeTextures();
  ~VolumeTextures();
  VolumeTextures(const VolumeTextures&) = delete;
  VolumeTextures& operator=(const VolumeTextures&) = delete;

  // The scan of the snapshot on screen; nothing is uploaded yet.
  void set(const std::shared_ptr<const VolumeImage>& image);
  // Uploads the intensities and/or the labels when the GPU does not hold this scan's yet.
  void prepare(bool intensity, bool labels);
  const std::shared_ptr<const VolumeImage>& image() const { return image_; }
  bool has_intensity() const { return image_ && image_->intensity; }
  bool has_labels() const { return image_ && image_->atlas; }
  // Binds the intensity texture to unit 1 and the labels to unit 2.
  void bind() const;
  // World millimetres -> intensity texture coordinates ((ijk + 1/2) / dims).
  glm::mat4 world_to_texture() const { return world_to_texture_; }
  // World millimetres -> label voxel index (centres at integers).
  glm::mat4 world_to_label() const { return world_to_label_; }
  int uploads() const { return uploads_; }
  double upload_ms() const { return upload_ms_; }  // spent uploading, all scans so far

 private:
  std::shared_ptr<const VolumeImage> image_;
  // The volumes the textures hold, kept alive so that a new volume can never be mistaken
  // for them by its address (an mri scene, another scene, then another scan).
  std::shared_ptr<const ScalarVolume> intensity_uploaded_;
  std::shared_ptr<const LabelAtlas> labels_uploaded_;
  unsigned intensity_texture_ = 0, label_texture_ = 0;
  glm::mat4 world_to_texture_{1.0f}, world_to_label_{1.0f};
  int uploads_ = 0;
  double upload_ms_ = 0.0;
};

// The inverse of a grid's voxel -> world map as a 4x4 matrix (world -> voxel index).
glm::mat4 world_to_voxel_matrix(const VoxelGrid& grid);

}  // namespace dynamesh
