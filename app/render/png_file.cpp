#include "app/render/png_file.h"

#include <stb_image_write.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/io/atomic_file.h"

namespace dynamesh {

void write_png(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::runtime_error("cannot write " + path + ": empty image");
  }
  std::vector<std::uint8_t> rgb(3 * static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    std::memcpy(&rgb[3 * i], &image.rgba[4 * i], 3);
  }
  // AtomicFile: complete or absent (also on Ctrl-C), and /dev/stdout written in place.
  AtomicFile file(path, std::ios::binary);
  const auto append = [](void* stream, void* data, int size) {
    static_cast<std::ostream*>(stream)->write(static_cast<const char*>(data), size);
  };
  if (stbi_write_png_to_func(append, &file.stream(), image.width, image.height, 3, rgb.data(),
                             3 * image.width) == 0)
    throw std::runtime_error("cannot write " + path + ": PNG encoding failed");
  file.commit();
}

}  // namespace dynamesh
