// PNG files for screenshots and rendered frames (stb_image_write).
#pragma once

#include <string>

#include "app/render/image.h"

namespace dynamesh {

// Writes `image` (alpha dropped: frames are opaque) to `path`. The data goes to a temporary
// name in the same directory first and is renamed into place once complete, so a crash or
// a full disk never leaves a partial file that looks complete. Throws std::runtime_error
// naming the path on failure.
void write_png(const Image& image, const std::string& path);

}  // namespace dynamesh
