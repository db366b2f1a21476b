#include "app/render/mesh_renderer.h"

#include <string>

#include "app/render/gl_api.h"
#include "app/render/shader_program.h"

namespace dynamesh {
namespace {
constexpr int kColormapTexels = 256;
}

MeshRenderer::MeshRenderer()
    : program_(
          std::make_unique<ShaderProgram>("mesh.vert.glsl", "mesh.geom.glsl", "mesh.frag.glsl")) {
  gl::GenTextures(1, &colormap_texture_);
  gl::BindTexture(GL_TEXTURE_2D, colormap_texture_);
  // Linear filtering would blend neighbouring categories: nearest, with enough texels that
  // continuous maps stay smooth.
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

MeshRenderer::~MeshRenderer() {
  gl::DeleteTextures(1, &colormap_texture_);
}

void MeshRenderer::set_geometry(const MeshSnapshot& snapshot) {
  mesh_.upload_geometry(snapshot);
  volume_.set(snapshot.volume);
  bounds_ = SceneBounds::from_points(snapshot.positions, snapshot.bounds);
}

void MeshRenderer::set_scalar(const MeshSnapshot& snapshot, ColorMode mode) {
  // Another mode is another field: its range starts again.
  if (mode != scalar_mode_ && !run_stats_given_) range_restarted_ = true;
  scalar_mode_ = mode;
  const std::string name(color_mode_field(mode));
  const ScalarField* field = name.empty() ? nullptr : snapshot.field(name);
  const bool usable = field != nullptr && field->values.size() == snapshot.n_vertices();
  scalar_stats_ = usable ? field_stats(field->values) : FieldStats{};
  if (mode == ColorMode::kIntensity && volume_.has_intensity()) {
    // The scan's robust window, the same for every frame and layer: grey values stay put.
    const Vec2 w = volume_.image()->window;
    scalar_stats_ = FieldStats{true,
                               static_cast<float>(w[0]),
                               static_cast<float>(w[1]),
                               static_cast<float>(w[0]),
                               static_cast<float>(w[1]),
                               static_cast<float>(0.5 * (w[0] + w[1])),
                               1};
  }
  if (range_restarted_ && scalar_stats_.present) {
    first_stats_ = scalar_stats_;
    if (!run_stats_given_) run_stats_ = scalar_stats_;
    range_restarted_ = false;
  } else if (!run_stats_given_) {
    run_stats_ = merge(run_stats_, scalar_stats_);
  }
  mesh_.upload_scalar(usable ? &field->values : nullptr);
}

bool MeshRenderer::samples_volume(ColorMode mode) const {
  return (mode == ColorMode::kIntensity && volume_.has_intensity()) ||
         (mode == ColorMode::kRegion && volume_.has_labels());
}

void MeshRenderer::restart_color_range(const FieldStats& whole_run) {
  range_restarted_ = true;
  run_stats_given_ = whole_run.present;
  run_stats_ = whole_run;
  first_stats_ = {};
}

bool MeshRenderer::shows_color_scale(const RenderStyle& style) const {
  return style.mode == scalar_mode_ && has_color_scale(style.mode, scalar_stats_);
}

ColorScale MeshRenderer::color_scale(const RenderStyle& style) const {
  const FieldStats* range = &scalar_stats_;
  // The scan's window is the same for every frame already (first frame = whole run).
  const bool fixed_by_scan = samples_volume(style.mode);
  if (!fixed_by_scan && style.colors.range == ColorRange::kFirstFrame && first_stats_.present)
    range = &first_stats_;
  if (!fixed_by_scan && style.colors.range == ColorRange::kRun && run_stats_.present)
    range = &run_stats_;
  return dynamesh::color_scale(style.mode, style.colors, *range);
}

void MeshRenderer::bind_colormap(ColormapId id) {
  gl::ActiveTexture(GL_TEXTURE0);
  gl::BindTexture(GL_TEXTURE_2D, colormap_texture_);
  if (colormap_loaded_ == static_cast<int>(id)) return;
  const std::vector<std::uint8_t> texels = colormap(id).table(kColormapTexels);
  gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kColormapTexels, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 texels.data());
  colormap_loaded_ = static_cast<int>(id);
}

void MeshRenderer::clear(const RenderStyle& style, const glm::ivec2& viewport_size) const {
  gl::Viewport(0, 0, viewport_size.x, viewport_size.y);
  gl::ClearColor(style.background.r, style.background.g, style.background.b, 1.0f);
  gl::Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void MeshRenderer::draw(const Camera& camera, const RenderStyle& style,
                        const glm::ivec2& viewport_size, const glm::ivec2& origin) {
  if (!has_mesh() || viewport_size.x <= 0 || viewport_size.y <= 0) return;
  const float aspect = static_cast<float>(viewport_size.x) / static_cast<float>(viewport_size.y);
  const glm::mat4 model_view = camera.view() * camera.model(bounds_);

  gl::Viewport(origin.x, origin.y, viewport_size.x, viewport_size.y);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LESS);
  gl::Disable(GL_CULL_FACE);  // back faces are drawn, in their own tint
  gl::Disable(GL_BLEND);

  const bool mapped = shows_color_scale(style);
  const ColorScale scale = color_scale(style);
  bind_colormap(scale.map);

  ShaderProgram& p = *program_;
  p.use();
  p.set("u_model_view", model_view);
  p.set("u_projection", camera.projection(aspect, bounds_));
  p.set("u_normal_matrix", glm::transpose(glm::inverse(glm::mat3(model_view))));
  p.set("u_viewport_size", glm::vec2(viewport_size));
  p.set("u_use_colormap", mapped);
  p.set("u_categorical", mapped && scale.discrete);
  p.set("u_colormap", 0);
  p.set("u_scalar_range", glm::vec2(scale.min, scale.max));
  p.set("u_surface_color", style.surface_color);
  p.set("u_backface_tint", style.backface_tint);
  p.set("u_wireframe", style.wireframe);
  p.set("u_wire_width", style.wire_width);
  p.set("u_wire_color", style.wire_color);
  p.set("u_light2_direction", glm::vec3(-0.5f, 0.8f, 0.35f));
  p.set("u_ambient", 0.22f);
  const bool from_volume = samples_volume(style.mode);
  p.set("u_volume_mode", !from_volume ? 0 : style.mode == ColorMode::kIntensity ? 1 : 2);
  p.set("u_intensity", 1);
  p.set("u_labels", 2);
  if (from_volume) {
    volume_.prepare(style.mode == ColorMode::kIntensity, style.mode == ColorMode::kRegion);
    volume_.bind();
    p.set("u_world_to_texture", volume_.world_to_texture());
    p.set("u_world_to_label", volume_.world_to_label());
  }
  mesh_.draw();
  gl::UseProgram(0);
}

}  // namespace dynamesh
