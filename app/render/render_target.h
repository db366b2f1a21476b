// An offscreen framebuffer of a given size: multisampled colour and depth to draw into, and
// a single-sample copy it resolves to for reading pixels or copying them to a window. Used for
// offscreen frames and for the viewer's 3D view (drawn again only when it changes).
#pragma once

#include <glm/glm.hpp>

#include "app/render/image.h"

namespace dynamesh {

class RenderTarget {
 public:
  // samples <= 1: no multisampling. Throws std::runtime_error when the framebuffer is
  // incomplete (e.g. a size beyond the implementation's limits).
  RenderTarget(int width, int height, int samples);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  glm::ivec2 size() const { return {width_, height_}; }
  // Makes this the draw framebuffer.
  void bind() const;
  // Resolves the samples and reads the picture (top row first); rebinds framebuffer 0.
  Image read();
  // Resolves the samples and copies the picture into framebuffer 0 (a window) with its
  // lower-left corner at `origin`; leaves framebuffer 0 bound.
  void present(const glm::ivec2& origin);

 private:
  unsigned make_framebuffer(int samples, unsigned& color, unsigned& depth) const;
  // The single-sample framebuffer holding the picture (resolving the samples first).
  unsigned resolved();

  int width_, height_, samples_;
  unsigned draw_fbo_ = 0, draw_color_ = 0, draw_depth_ = 0;
  unsigned resolve_fbo_ = 0, resolve_color_ = 0, resolve_depth_ = 0;
};

}  // namespace dynamesh
