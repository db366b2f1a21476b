// MeshRenderer: draws a MeshSnapshot with OpenGL 3.3 core — smooth two-light shading,
// back faces tinted, a constant-width wireframe in the same pass (geometry shader), and
// colour modes mapping a per-vertex field through a colour map. Works on any context whose
// functions were loaded with gl::load_functions (OSMesa offscreen, GLFW in the viewer).
//
// A snapshot that carries its scan (mri) is coloured per fragment from it in the intensity
// and region modes (volume_textures.h); the scan goes to the GPU once, not per snapshot.
//
// Use: set_mesh() when a new snapshot arrives (uploads once; positions only when the
// connectivity is unchanged), set_scalar() when only the colour mode changes, then
// clear() + draw() every frame.
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "app/render/camera.h"
#include "app/render/color_scale.h"
#include "app/render/gpu_mesh.h"
#include "app/render/render_style.h"
#include "app/render/volume_textures.h"
#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

class ShaderProgram;

class MeshRenderer {
 public:
  // Needs a current context with the GL functions loaded; throws std::runtime_error when the
  // shaders do not build.
  MeshRenderer();
  ~MeshRenderer();
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  void set_mesh(const MeshSnapshot& snapshot, ColorMode mode) {
    set_geometry(snapshot);
    set_scalar(snapshot, mode);
  }
  void set_geometry(const MeshSnapshot& snapshot);
  void set_scalar(const MeshSnapshot& snapshot, ColorMode mode);

  // Clears colour and depth of the bound framebuffer to the style's background.
  void clear(const RenderStyle& style, const glm::ivec2& viewport_size) const;
  // Draws into the viewport of `viewport_size` pixels whose lower-left corner is `origin`.
  void draw(const Camera& camera, const RenderStyle& style, const glm::ivec2& viewport_size,
            const glm::ivec2& origin = glm::ivec2(0));

  bool has_mesh() const { return mesh_.n_triangles() > 0; }
  const SceneBounds& bounds() const { return bounds_; }
  // The scale the surface is coloured with under `style`; false when drawn flat.
  bool shows_color_scale(const RenderStyle& style) const;
  ColorScale color_scale(const RenderStyle& style) const;
  const FieldStats& scalar_stats() const { return scalar_stats_; }
  // The next field shown starts the range of ColorRange::kFirstFrame and kRun again (a new
  // run). With `whole_run`, kRun spans exactly these values (a batch render that knows the
  // whole run before drawing it) instead of growing with each field shown.
  void restart_color_range(const FieldStats& whole_run = {});
  const UploadCounters& uploads() const { return mesh_.counters(); }
  // The scan of the last snapshot (null for analytic scenes) and how often it was uploaded.
  const std::shared_ptr<const VolumeImage>& volume() const { return volume_.image(); }
  int volume_uploads() const { return volume_.uploads(); }
  double volume_upload_ms() const { return volume_.upload_ms(); }
  // Whether `mode` is drawn from the scan per fragment (intensity, region) rather than from
  // a per-vertex field.
  bool samples_volume(ColorMode mode) const;
  std::size_t n_triangles() const { return mesh_.n_triangles(); }

 private:
  void bind_colormap(ColormapId id);

  std::unique_ptr<ShaderProgram> program_;
  GpuMesh mesh_;
  VolumeTextures volume_;
  SceneBounds bounds_;
  ColorMode scalar_mode_ = ColorMode::kShaded;
  FieldStats scalar_stats_;
  FieldStats first_stats_, run_stats_;  // since restart_color_range(), in scalar_mode_
  bool range_restarted_ = true, run_stats_given_ = false;
  unsigned colormap_texture_ = 0;
  int colormap_loaded_ = -1;  // ColormapId in the texture, -1 before the first upload
};

}  // namespace dynamesh
