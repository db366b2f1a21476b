#include "app/offscreen/osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

#include "app/render/gl_loader.h"

namespace dynamesh {

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer = std::vector<unsigned char>(4);
};

namespace {

gl::ProcAddress osmesa_proc(const char* name) {
  return reinterpret_cast<gl::ProcAddress>(OSMesaGetProcAddress(name));
}

}  // namespace

OsmesaContext::OsmesaContext() : impl_(std::make_unique<Impl>()) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl_->context == nullptr) {
    throw std::runtime_error("OSMesa cannot create an OpenGL 3.3 core context");
  }
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(impl_->context);
    throw std::runtime_error("OSMesa cannot make its context current");
  }
  const std::string missing = gl::load_functions(osmesa_proc);
  if (!missing.empty()) {
    OSMesaDestroyContext(impl_->context);
    throw std::runtime_error("OSMesa lacks OpenGL functions: " + missing);
  }
}

OsmesaContext::~OsmesaContext() {
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

std::string OsmesaContext::description() const {
  const auto get = reinterpret_cast<const GLubyte* (*)(GLenum)>(osmesa_proc("glGetString"));
  return std::string("OpenGL ") + reinterpret_cast<const char*>(get(GL_VERSION)) + " (" +
         reinterpret_cast<const char*>(get(GL_RENDERER)) + ")";
}

}  // namespace dynamesh
