#include "app/render/colormap.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {
namespace {

glm::vec3 rgb(int r, int g, int b) {
  return glm::vec3(r, g, b) / 255.0f;
}

std::vector<Colormap> make_colormaps() {
  return {
      {ColormapId::kErrorYellowGreenRed,
       "yellow-green-red",
       {rgb(255, 240, 30), rgb(140, 210, 40), rgb(30, 160, 60), rgb(200, 120, 30),
        rgb(220, 30, 30)}},
      // Viridis sampled at nine evenly spaced points (matplotlib's published values).
      {ColormapId::kViridis,
       "viridis",
       {rgb(68, 1, 84), rgb(71, 44, 122), rgb(59, 81, 139), rgb(44, 113, 142), rgb(33, 144, 141),
        rgb(39, 173, 129), rgb(92, 200, 99), rgb(170, 220, 50), rgb(253, 231, 37)}},
      {ColormapId::kCoolWarm,
       "cool-warm",
       {rgb(59, 76, 192), rgb(141, 176, 254), rgb(221, 221, 221), rgb(244, 154, 123),
        rgb(180, 4, 38)}},
      {ColormapId::kGray, "gray", {rgb(0, 0, 0), rgb(255, 255, 255)}},
      {ColormapId::kCategorical,
       "categorical",
       {rgb(120, 80, 160), rgb(60, 130, 200), rgb(90, 180, 90), rgb(240, 200, 60),
        rgb(240, 130, 50), rgb(210, 50, 50), rgb(150, 40, 90), rgb(90, 90, 90)},
       true},
  };
}

}  // namespace

glm::vec3 Colormap::sample(float t) const {
  t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f);
  const int n = static_cast<int>(colors.size());
  if (categorical) return colors[std::min(n - 1, static_cast<int>(t * static_cast<float>(n)))];
  const float x = t * static_cast<float>(n - 1);
  const int i = std::min(n - 2, static_cast<int>(x));
  return glm::mix(colors[i], colors[i + 1], x - static_cast<float>(i));
}

std::vector<std::uint8_t> Colormap::table(int n) const {
  std::vector<std::uint8_t> texels(4 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const glm::vec3 c = sample((static_cast<float>(i) + 0.5f) / static_cast<float>(n));
    for (int k = 0; k < 3; ++k) texels[4 * i + k] = static_cast<std::uint8_t>(c[k] * 255.0f + 0.5f);
    texels[4 * i + 3] = 255;
  }
  return texels;
}

const Colormap& colormap(ColormapId id) {
  static const std::vector<Colormap> maps = make_colormaps();  // immutable table, not state
  for (const Colormap& m : maps) {
    if (m.id == id) return m;
  }
  return maps.front();
}

}  // namespace dynamesh
