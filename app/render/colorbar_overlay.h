// A colour bar with numbers, painted into an image on the CPU: offscreen frames have no UI
// toolkit, so the bar and its labels (stb_easy_font's bitmap glyphs) are drawn after the
// frame is read back. The viewer draws its own bar with ImGui.
#pragma once

#include <string>

#include "app/render/color_scale.h"
#include "app/render/image.h"

namespace dynamesh {

// Bar on the right-hand side, labels (title, ends, middle; each integer for a discrete
// scale) to its left. Text scale grows with the image height.
void draw_colorbar(Image& image, const ColorScale& scale);

// Width of the strip on the right that the bar and its labels need: the 3D view is drawn
// beside it, not under it.
int colorbar_strip_width(int width, int height, const ColorScale& scale);

// Number as printed on colour bars: 3 significant digits.
std::string colorbar_label(double value);

}  // namespace dynamesh
