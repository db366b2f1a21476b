#include "app/render/render_target.h"

#include <stdexcept>
#include <string>

#include "app/render/gl_api.h"

namespace dynamesh {

RenderTarget::RenderTarget(int width, int height, int samples)
    : width_(width), height_(height), samples_(samples > 1 ? samples : 0) {
  if (width <= 0 || height <= 0) throw std::runtime_error("render target: empty size");
  draw_fbo_ = make_framebuffer(samples_, draw_color_, draw_depth_);
  if (samples_ > 0) resolve_fbo_ = make_framebuffer(0, resolve_color_, resolve_depth_);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

RenderTarget::~RenderTarget() {
  const unsigned fbos[2] = {draw_fbo_, resolve_fbo_};
  const unsigned rbos[4] = {draw_color_, draw_depth_, resolve_color_, resolve_depth_};
  gl::DeleteFramebuffers(2, fbos);
  gl::DeleteRenderbuffers(4, rbos);
}

unsigned RenderTarget::make_framebuffer(int samples, unsigned& color, unsigned& depth) const {
  unsigned fbo = 0;
  gl::GenFramebuffers(1, &fbo);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl::GenRenderbuffers(1, &color);
  gl::BindRenderbuffer(GL_RENDERBUFFER, color);
  gl::RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width_, height_);
  gl::FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  gl::GenRenderbuffers(1, &depth);
  gl::BindRenderbuffer(GL_RENDERBUFFER, depth);
  gl::RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width_,
                                     height_);
  gl::FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  const GLenum status = gl::CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("render target " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " incomplete (status " +
                             std::to_string(status) + ")");
  }
  return fbo;
}

void RenderTarget::bind() const {
  gl::BindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  gl::Viewport(0, 0, width_, height_);
}

unsigned RenderTarget::resolved() {
  if (samples_ == 0) return draw_fbo_;
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_);
  gl::BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  gl::BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  return resolve_fbo_;
}

Image RenderTarget::read() {
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, resolved());
  gl::ReadBuffer(GL_COLOR_ATTACHMENT0);
  Image image = read_framebuffer(width_, height_);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

void RenderTarget::present(const glm::ivec2& origin) {
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, resolved());
  gl::BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl::BlitFramebuffer(0, 0, width_, height_, origin.x, origin.y, origin.x + width_,
                      origin.y + height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace dynamesh
