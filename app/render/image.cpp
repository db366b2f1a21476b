#include "app/render/image.h"

#include <algorithm>

#include "app/render/gl_api.h"

namespace dynamesh {

void Image::flip_rows() {
  const std::size_t row = 4 * static_cast<std::size_t>(width);
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(rgba.begin() + static_cast<std::ptrdiff_t>(y * row),
                     rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     rgba.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  }
}

Image read_framebuffer(int width, int height) {
  Image image(width, height);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  image.flip_rows();
  return image;
}

}  // namespace dynamesh
