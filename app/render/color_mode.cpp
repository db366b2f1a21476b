#include "app/render/color_mode.h"

namespace dynamesh {
namespace {

struct ModeInfo {
  ColorMode mode;
  std::string_view name, field, label;
};

constexpr ModeInfo kModes[] = {
    {ColorMode::kShaded, "shaded", "", "shaded"},
    {ColorMode::kError, "error", "error", "sampled error"},
    {ColorMode::kCurvature, "curvature", "curvature", "curvature"},
    {ColorMode::kValence, "valence", "valence", "valence"},
    {ColorMode::kLevel, "level", "level", "refinement level"},
    {ColorMode::kIntensity, "intensity", "intensity", "MR intensity"},
    {ColorMode::kRegion, "region", "", "anatomical region"},
};

const ModeInfo& info(ColorMode mode) {
  for (const ModeInfo& m : kModes) {
    if (m.mode == mode) return m;
  }
  return kModes[0];
}

}  // namespace

std::string_view color_mode_name(ColorMode mode) {
  return info(mode).name;
}
std::string_view color_mode_field(ColorMode mode) {
  return info(mode).field;
}
std::string_view color_mode_label(ColorMode mode) {
  return info(mode).label;
}

std::optional<ColorMode> parse_color_mode(std::string_view name) {
  for (const ModeInfo& m : kModes) {
    if (m.name == name) return m.mode;
  }
  return std::nullopt;
}

}  // namespace dynamesh
