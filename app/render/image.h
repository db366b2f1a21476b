// An 8-bit RGBA image, rows from top to bottom (file order; OpenGL reads bottom-up).
#pragma once

#include <cstdint>
#include <vector>

namespace dynamesh {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(4 * static_cast<std::size_t>(w) * h, 0) {}

  std::uint8_t* pixel(int x, int y) { return &rgba[4 * (static_cast<std::size_t>(y) * width + x)]; }
  const std::uint8_t* pixel(int x, int y) const {
    return &rgba[4 * (static_cast<std::size_t>(y) * width + x)];
  }
  void flip_rows();
};

// Reads the bound read framebuffer's colour (the area [0, width) x [0, height)) into an
// image, top row first.
Image read_framebuffer(int width, int height);

}  // namespace dynamesh
