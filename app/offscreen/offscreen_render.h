// Offscreen rendering to images and PNG files with the same MeshRenderer as the viewer, on a
// software OSMesa context: what `dynamesh-cli run ... --render DIR` uses, and the tests.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "app/render/camera.h"
#include "app/render/color_scale.h"
#include "app/render/gpu_mesh.h"
#include "app/render/image.h"
#include "app/render/render_style.h"
#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

struct OffscreenOptions {
  int width = 1024;
  int height = 768;
  int samples = 4;  // multisampling (anti-aliased silhouettes); 1 turns it off
  // Colour mode (style.mode), error threshold (style.colors.threshold), wireframe, tints.
  RenderStyle style;
  // The view. Absent: the default three-quarter view fitted to the first frame, kept for
  // later frames so that motion shows (unless refit_each_frame).
  std::optional<Camera> camera;
  // Without `camera`: the view it is fitted with (--camera; default: three-quarter, fitted).
  CameraView view;
  bool refit_each_frame = false;
  bool normalize_size = false;  // scale the surface to a common size (see Camera)
  // A colour bar with numbers on the right, for scalar colour modes.
  bool colorbar = true;
};

// Keeps one context, renderer and framebuffer across frames: an animation re-uploads only
// what changed between snapshots. Not thread-safe; one per thread.
class OffscreenRenderer {
 public:
  // Throws std::runtime_error when no OpenGL 3.3 core context can be made.
  OffscreenRenderer();
  ~OffscreenRenderer();

  Image render(const MeshSnapshot& snapshot, const OffscreenOptions& options);
  // Renders and writes a PNG (atomically: temporary name, then rename).
  void render_to_png(const MeshSnapshot& snapshot, const OffscreenOptions& options,
                     const std::string& path);
  // ColorRange::kFirstFrame and kRun start again with the next frame; kRun spans
  // `whole_run` when given (MeshRenderer::restart_color_range).
  void restart_color_range(const FieldStats& whole_run = {});
  // The camera used for the last frame (fitted or given).
  const Camera& camera() const;
  // How often mesh data went to the GPU (full / positions only / colour field).
  const UploadCounters& uploads() const;
  // "OpenGL <version> (<renderer>)".
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot conveniences (create a context each call).
Image render_to_image(const MeshSnapshot& snapshot, const OffscreenOptions& options);
void render_to_png(const MeshSnapshot& snapshot, const OffscreenOptions& options,
                   const std::string& path);

}  // namespace dynamesh
