#include "app/offscreen/offscreen_render.h"

#include <stdexcept>

#include "app/offscreen/osmesa_context.h"
#include "app/render/colorbar_overlay.h"
#include "app/render/mesh_renderer.h"
#include "app/render/png_file.h"
#include "app/render/render_target.h"

namespace dynamesh {

struct OffscreenRenderer::Impl {
  OsmesaContext context;
  MeshRenderer renderer;
  std::unique_ptr<RenderTarget> target;
  Camera camera;
  bool camera_fitted = false;

  RenderTarget& target_for(const OffscreenOptions& o) {
    if (!target || target->size() != glm::ivec2(o.width, o.height)) {
      target.reset();  // free the old buffers before allocating new ones
      target = std::make_unique<RenderTarget>(o.width, o.height, o.samples);
    }
    return *target;
  }

  void choose_camera(const OffscreenOptions& o, const glm::ivec2& view) {
    const float aspect = static_cast<float>(view.x) / static_cast<float>(view.y);
    if (o.camera) {
      camera = *o.camera;
      return;
    }
    camera.normalize_size = o.normalize_size;
    if (!camera_fitted || o.refit_each_frame) camera.look(o.view, renderer.bounds(), aspect);
    camera_fitted = true;
  }
};

OffscreenRenderer::OffscreenRenderer() : impl_(std::make_unique<Impl>()) {}
OffscreenRenderer::~OffscreenRenderer() = default;

Image OffscreenRenderer::render(const MeshSnapshot& snapshot, const OffscreenOptions& o) {
  if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384) {
    throw std::invalid_argument("image size must be between 1x1 and 16384x16384");
  }
  Impl& m = *impl_;
  m.renderer.set_mesh(snapshot, o.style.mode);
  const bool bar = o.colorbar && m.renderer.shows_color_scale(o.style);
  const ColorScale scale = m.renderer.color_scale(o.style);
  // The view takes the image left of the colour bar's strip.
  const glm::ivec2 view(o.width - (bar ? colorbar_strip_width(o.width, o.height, scale) : 0),
                        o.height);
  m.choose_camera(o, view);
  RenderTarget& target = m.target_for(o);
  target.bind();
  m.renderer.clear(o.style, target.size());
  m.renderer.draw(m.camera, o.style, view);
  Image image = target.read();
  if (bar) draw_colorbar(image, scale);
  return image;
}

void OffscreenRenderer::render_to_png(const MeshSnapshot& snapshot, const OffscreenOptions& o,
                                      const std::string& path) {
  write_png(render(snapshot, o), path);
}

void OffscreenRenderer::restart_color_range(const FieldStats& whole_run) {
  impl_->renderer.restart_color_range(whole_run);
}

const Camera& OffscreenRenderer::camera() const {
  return impl_->camera;
}

const UploadCounters& OffscreenRenderer::uploads() const {
  return impl_->renderer.uploads();
}

std::string OffscreenRenderer::description() const {
  return impl_->context.description();
}

Image render_to_image(const MeshSnapshot& snapshot, const OffscreenOptions& options) {
  OffscreenRenderer renderer;
  return renderer.render(snapshot, options);
}

void render_to_png(const MeshSnapshot& snapshot, const OffscreenOptions& options,
                   const std::string& path) {
  write_png(render_to_image(snapshot, options), path);
}

}  // namespace dynamesh
