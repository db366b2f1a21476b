// Colour maps from [0, 1] to RGB, defined by a few control colours and linear (or, for
// categorical maps, piecewise-constant) interpolation between them. The same definition feeds
// the GPU texture, the ImGui colour bar and the offscreen colour bar.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace dynamesh {

enum class ColormapId {
  kErrorYellowGreenRed,  // the paper's error colouring: yellow = none, green, red = threshold
  kViridis,              // perceptually uniform alternative
  kCoolWarm,             // diverging, for signed values (curvature)
  kGray,                 // intensity images
  kCategorical,          // distinct colours for small integers (valence)
};

struct Colormap {
  ColormapId id;
  std::string_view name;
  std::vector<glm::vec3> colors;  // evenly spaced over [0, 1] (bin centres if categorical)
  bool categorical = false;

  glm::vec3 sample(float t) const;
  // `n` RGBA8 texels sampling the map at bin centres.
  std::vector<std::uint8_t> table(int n) const;
};

const Colormap& colormap(ColormapId id);

}  // namespace dynamesh
