#include "app/render/colorbar_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <stb_easy_font.h>

namespace dynamesh {
namespace {

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const glm::vec3& color) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image.width);
  y1 = std::min(y1, image.height);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(color[k] * 255.0f + 0.5f);
      p[3] = 255;
    }
  }
}

// stb_easy_font emits axis-aligned quads (4 vertices of 16 bytes: x, y, z, colour).
int text_width(const std::string& text, int scale) {
  return scale * stb_easy_font_width(const_cast<char*>(text.c_str()));
}

void draw_text(Image& image, int x, int y, const std::string& text, int scale) {
  std::vector<char> buffer(text.size() * 1024 + 64);  // up to ~14 quads of 64 bytes a glyph
  const int quads = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(text.c_str()), nullptr,
                                        buffer.data(), static_cast<int>(buffer.size()));
  const auto* v = reinterpret_cast<const float*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const float* a = v + 16 * q;  // vertex 0 (x, y at floats 0, 1)
    const float* c = a + 8;       // vertex 2, the opposite corner
    fill_rect(image, x + scale * static_cast<int>(a[0]), y + scale * static_cast<int>(a[1]),
              x + scale * static_cast<int>(c[0]), y + scale * static_cast<int>(c[1]),
              glm::vec3(0.1f));
  }
}

}  // namespace

std::string colorbar_label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", std::abs(value) < 1e-12 ? 0.0 : value);
  return text;
}

namespace {

int text_scale(int height) {
  return std::max(1, (height + 120) / 240);
}  // glyphs: 7 px high
int bar_width(int width) {
  return std::max(8, width / 40);
}

}  // namespace

int colorbar_strip_width(int width, int height, const ColorScale& scale) {
  const int s = text_scale(height);
  const int labels =
      std::max(text_width(colorbar_label(scale.min), s), text_width(colorbar_label(scale.max), s));
  const int strip = std::max(text_width(scale.label, s), labels + 4 * s + bar_width(width));
  return std::min(width / 2, strip + 12 * s);
}

void draw_colorbar(Image& image, const ColorScale& scale) {
  const int s = text_scale(image.height);
  const int bar_w = bar_width(image.width);
  const int bar_h = image.height / 2;
  const int x0 = image.width - bar_w - 6 * s;
  const int y0 = (image.height - bar_h) / 2;
  const Colormap& map = colormap(scale.map);
  for (int y = 0; y < bar_h; ++y) {
    const float t = 1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(bar_h);
    fill_rect(image, x0, y0 + y, x0 + bar_w, y0 + y + 1, map.sample(t));
  }
  const auto label_at = [&](double value) {
    const double t = (value - scale.min) / (scale.max - scale.min);
    const int y = y0 + static_cast<int>((1.0 - t) * bar_h) - 3 * s;
    const std::string text = colorbar_label(value);
    draw_text(image, x0 - 4 * s - text_width(text, s), y, text, s);
  };
  if (scale.discrete) {
    // At least two text heights (7 s) apart: a deep mesh's levels are thinned.
    for (int v : discrete_labels(scale, bar_h / (14 * s))) label_at(v);
  } else {
    for (double f : {0.0, 0.5, 1.0}) label_at(scale.min + f * (scale.max - scale.min));
  }
  const int title_x = std::max(0, image.width - 6 * s - text_width(scale.label, s));
  draw_text(image, title_x, y0 - 12 * s, scale.label, s);
}

}  // namespace dynamesh
