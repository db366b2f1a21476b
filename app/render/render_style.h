// How a mesh is drawn: colour mode and its settings, wireframe, tints. Plain data, so the
// viewer can keep it in its one state struct and the offscreen renderer in its options.
#pragma once

#include <glm/glm.hpp>

#include "app/render/color_mode.h"

namespace dynamesh {

// Which values a scale taken from the data (curvature, MR intensity, level) spans: each
// frame's own (a video of a changing field flickers), the first frame's, the whole run's
// (the viewer: every step since the last restart), or a range typed by the user.
enum class ColorRange { kFrame, kFirstFrame, kRun, kFixed };

struct ColorSettings {
  double threshold = 0.008;    // error mode: red at and beyond this (the adapter's T)
  bool error_viridis = false;  // error mode: viridis instead of yellow-green-red
  // intensity: the scan's robust window (1st-99th percentile inside the brain; without a
  // scan, the field's 2nd-98th percentiles) instead of intensity_window / intensity_level.
  bool intensity_auto = true;
  double intensity_window = 100.0;  // intensity: width of the ramp
  double intensity_level = 50.0;    // intensity: value shown mid-ramp
  bool intensity_viridis = false;   // intensity: viridis (perceptual) instead of grey
  ColorRange range = ColorRange::kFrame;
  double range_min = 0.0, range_max = 1.0;  // kFixed: the values at the map's two ends

  bool operator==(const ColorSettings&) const = default;
};

struct RenderStyle {
  ColorMode mode = ColorMode::kShaded;
  ColorSettings colors;
  bool wireframe = true;
  float wire_width = 1.0f;  // pixels
  glm::vec3 wire_color{0.12f, 0.12f, 0.14f};
  glm::vec3 surface_color{0.72f, 0.76f, 0.82f};
  glm::vec3 backface_tint{0.75f, 0.35f, 0.30f};
  glm::vec3 background{0.93f, 0.94f, 0.95f};

  bool operator==(const RenderStyle&) const = default;
};

}  // namespace dynamesh
