#include "app/render/png_file.h"

#include <stb_image_write.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace dynamesh {

void write_png(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::runtime_error("cannot write " + path + ": empty image");
  }
  std::vector<std::uint8_t> rgb(3 * static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    std::memcpy(&rgb[3 * i], &image.rgba[4 * i], 3);
  }
  // The temporary name is unique per process, so parallel writers never collide.
  const std::string temp = path + ".tmp" + std::to_string(::getpid());
  if (stbi_write_png(temp.c_str(), image.width, image.height, 3, rgb.data(), 3 * image.width) ==
      0) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  std::error_code error;
  std::filesystem::rename(temp, path, error);
  if (error) {
    std::filesystem::remove(temp, error);
    throw std::runtime_error("cannot write " + path + ": " + error.message());
  }
}

}  // namespace dynamesh
