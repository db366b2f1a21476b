#include "app/render/gl_api.h"

namespace dynamesh::gl {

#define DYNAMESH_GL_DEFINE(UPPER, Name) PFNGL##UPPER##PROC Name = nullptr;
DYNAMESH_GL_FUNCTIONS(DYNAMESH_GL_DEFINE)
#undef DYNAMESH_GL_DEFINE

namespace {
bool g_loaded = false;
}

std::string load_functions(ProcLoader loader) {
  std::string missing;
#define DYNAMESH_GL_LOAD(UPPER, Name)                              \
  Name = reinterpret_cast<PFNGL##UPPER##PROC>(loader("gl" #Name)); \
  if (Name == nullptr) missing += (missing.empty() ? "gl" : " gl") + std::string(#Name);
  DYNAMESH_GL_FUNCTIONS(DYNAMESH_GL_LOAD)
#undef DYNAMESH_GL_LOAD
  g_loaded = missing.empty();
  return missing;
}

bool functions_loaded() {
  return g_loaded;
}

}  // namespace dynamesh::gl
