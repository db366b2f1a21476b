// What the surface colour shows. Shared by the viewer, the offscreen renderer and the CLI
// (`--color error|curvature|intensity|valence|level|shaded`).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace dynamesh {

// kIntensity and kRegion come from the scan itself where the snapshot carries one (mri): the
// renderer samples its 3-D texture per fragment (kIntensity falls back to the per-vertex
// "intensity" field without it).
enum class ColorMode { kShaded, kError, kCurvature, kValence, kLevel, kIntensity, kRegion };

inline constexpr std::array<ColorMode, 7> kAllColorModes = {
    ColorMode::kShaded, ColorMode::kError,     ColorMode::kCurvature, ColorMode::kValence,
    ColorMode::kLevel,  ColorMode::kIntensity, ColorMode::kRegion};

// Command-line name: "shaded", "error", "curvature", "valence", "level", "intensity",
// "region".
std::string_view color_mode_name(ColorMode mode);
std::optional<ColorMode> parse_color_mode(std::string_view name);
// Name of the MeshSnapshot field the mode shows; empty for kShaded.
std::string_view color_mode_field(ColorMode mode);
// Human label for panels and colour bars, e.g. "sampled error".
std::string_view color_mode_label(ColorMode mode);

}  // namespace dynamesh
