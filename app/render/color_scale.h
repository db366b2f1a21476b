// The mapping from a scalar field's values to colours for one colour mode: which map, and
// which values land on its two ends. Used by the renderer and by both colour bars.
#pragma once

#include <string>
#include <vector>

#include "app/render/colormap.h"
#include "app/render/render_style.h"

namespace dynamesh {

// Summary of a field's values, computed once per snapshot (robust ends ignore outliers).
struct FieldStats {
  bool present = false;
  float min = 0.0f, max = 0.0f;
  float low = 0.0f, high = 0.0f;  // 2nd and 98th percentiles
  float mean = 0.0f;
  std::size_t count = 0;  // finite values
};

FieldStats field_stats(const std::vector<float>& values);
// The summary of both fields' values together (percentiles: the wider of the two).
FieldStats merge(const FieldStats& a, const FieldStats& b);

// --color-range: "frame", "first", "run" or "MIN,MAX". Throws std::invalid_argument.
void parse_color_range(const std::string& text, ColorSettings& into);
// The text parse_color_range reads back.
std::string color_range_text(const ColorSettings& settings);

struct ColorScale {
  ColormapId map = ColormapId::kViridis;
  float min = 0.0f, max = 1.0f;  // values at the map's ends (clamped beyond)
  bool discrete = false;         // integer-valued (valence): one bin per integer
  std::string label;             // e.g. "sampled error"
};

// A scale taken from a field's values (curvature, automatic intensity window) spans at
// least this fraction of the field's mean magnitude: a nearly constant field (the curvature
// of a sphere, equal up to rounding) shows as one colour, not as its rounding noise spread
// over the whole map.
inline constexpr float kMinRelativeRange = 0.2f;

// The integers a discrete scale's bar labels: every one when at most `max_labels` fit, else
// the multiples of 2, 5, 10, 20, 50, ... (the first that fit), so a deep mesh's levels
// 0 .. 30 read 0, 5, 10, ... instead of thirty-one overlapping numbers.
std::vector<int> discrete_labels(const ColorScale& scale, int max_labels);

// kShaded (or an absent field) gives no scale: the surface is drawn in its flat tint.
bool has_color_scale(ColorMode mode, const FieldStats& stats);
ColorScale color_scale(ColorMode mode, const ColorSettings& settings, const FieldStats& stats);

}  // namespace dynamesh
