// GLSL sources of shaders/, embedded into the binary at build time (see
// app/cmake/embed_shaders.cmake), looked up by file name.
#pragma once

#include <string_view>

namespace dynamesh {

// The text of shaders/<name> (e.g. "mesh.vert.glsl"); empty when there is no such file.
std::string_view shader_source(std::string_view name);

}  // namespace dynamesh
