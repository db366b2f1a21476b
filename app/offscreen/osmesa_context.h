// A software OpenGL 3.3 core context (OSMesa, llvmpipe): rendering without a display or a
// GPU, for the batch command line and the tests.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace dynamesh {

class OsmesaContext {
 public:
  // Creates the context, makes it current on this thread and loads the renderer's GL
  // functions. The context's own framebuffer is a token 1x1 buffer: frames are drawn into
  // RenderTargets. Throws std::runtime_error when OSMesa cannot provide OpenGL 3.3 core.
  OsmesaContext();
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  // "OpenGL <version> (<renderer>)", for logs.
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynamesh
