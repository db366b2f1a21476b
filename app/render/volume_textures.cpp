#include "app/render/volume_textures.h"

#include <chrono>

#include <glm/gtc/matrix_transform.hpp>

#include "app/render/gl_api.h"

namespace dynamesh {
namespace {

void make_texture(unsigned texture, int filter) {
  gl::BindTexture(GL_TEXTURE_3D, texture);
  gl::TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, filter);
  gl::TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, filter);
  // Beyond the outermost voxel centres: the nearest one's value (as TrilinearSampler).
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl::TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
}

}  // namespace

glm::mat4 world_to_voxel_matrix(const VoxelGrid& grid) {
  glm::mat4 m(1.0f);  // voxel -> world, column-major
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) m[c][r] = static_cast<float>(grid.linear(r, c));
    m[3][c] = static_cast<float>(grid.offset[c]);
  }
  // In double on the CPU would be more exact; the map is well conditioned (the NIfTI reader
  // refuses degenerate ones) and voxel indices are ~100, so float keeps ~1e-5 voxel.
  return glm::inverse(m);
}

VolumeTextures::VolumeTextures() {
  unsigned textures[2];
  gl::GenTextures(2, textures);
  intensity_texture_ = textures[0];
  label_texture_ = textures[1];
  make_texture(intensity_texture_, GL_LINEAR);
  make_texture(label_texture_, GL_NEAREST);  // integer textures cannot be filtered
}

VolumeTextures::~VolumeTextures() {
  const unsigned textures[2] = {intensity_texture_, label_texture_};
  gl::DeleteTextures(2, textures);
}

void VolumeTextures::set(const std::shared_ptr<const VolumeImage>& image) {
  image_ = image;
}

void VolumeTextures::prepare(bool intensity, bool labels) {
  const std::shared_ptr<const VolumeImage>& image = image_;
  if (!image) return;
  const auto start = std::chrono::steady_clock::now();
  const int uploads_before = uploads_;
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (intensity && image->intensity && image->intensity != intensity_uploaded_) {
    const ScalarVolume& v = *image->intensity;
    gl::BindTexture(GL_TEXTURE_3D, intensity_texture_);
    gl::TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, v.grid.dims[0], v.grid.dims[1], v.grid.dims[2], 0,
                   GL_RED, GL_FLOAT, v.values.data());
    const glm::vec3 dims(v.grid.dims[0], v.grid.dims[1], v.grid.dims[2]);
    // Texel centres sit at (index + 1/2) / size.
    world_to_texture_ = glm::scale(glm::mat4(1.0f), 1.0f / dims) *
                        glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                        world_to_voxel_matrix(v.grid);
    intensity_uploaded_ = image->intensity;
    ++uploads_;
  }
  if (labels && image->atlas && image->atlas != labels_uploaded_) {
    const VoxelVolume<std::int32_t>& l = image->atlas->labels;
    gl::BindTexture(GL_TEXTURE_3D, label_texture_);
    gl::TexImage3D(GL_TEXTURE_3D, 0, GL_R32I, l.grid.dims[0], l.grid.dims[1], l.grid.dims[2], 0,
                   GL_RED_INTEGER, GL_INT, l.values.data());
    world_to_label_ = world_to_voxel_matrix(l.grid);
    labels_uploaded_ = image->atlas;
    ++uploads_;
  }
  if (uploads_ != uploads_before)
    upload_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void VolumeTextures::bind() const {
  gl::ActiveTexture(GL_TEXTURE1);
  gl::BindTexture(GL_TEXTURE_3D, intensity_texture_);
  gl::ActiveTexture(GL_TEXTURE2);
  gl::BindTexture(GL_TEXTURE_3D, label_texture_);
  gl::ActiveTexture(GL_TEXTURE0);
}

}  // namespace dynamesh
