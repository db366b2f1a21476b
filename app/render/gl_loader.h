// Loading the renderer's OpenGL entry points from a context. Kept free of GL headers so that
// platform code (which includes its own, e.g. osmesa.h) can call it.
#pragma once

#include <string>

namespace dynamesh::gl {

using ProcAddress = void (*)();
using ProcLoader = ProcAddress (*)(const char* name);

// Loads every function of gl_api.h through `loader` for the context current on this thread.
// Returns an empty string on success, else the names that could not be found. Contexts
// from one GL library share entry points, so one successful load serves all of them.
std::string load_functions(ProcLoader loader);

// True once load_functions() succeeded.
bool functions_loaded();

}  // namespace dynamesh::gl
