#include "app/viewer/slice_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "app/render/gl_api.h"

namespace dynamesh {
namespace {

constexpr const char* kSliceNames[3] = {"slice_i", "slice_j", "slice_k"};
constexpr const char* kSliceTitles[3] = {"i (sagittal)", "j (coronal)", "k (axial)"};

}  // namespace

std::array<int, 2> slice_axes(int axis) {
  return axis == 0   ? std::array<int, 2>{1, 2}
         : axis == 1 ? std::array<int, 2>{0, 2}
                     : std::array<int, 2>{0, 1};
}

SlicePanel::~SlicePanel() {
  for (Slice& s : slices_)
    if (s.texture != 0) gl::DeleteTextures(1, &s.texture);
}

void SlicePanel::update_texture(Slice& s, int axis, int index,
                                const std::shared_ptr<const ScalarVolume>& volume,
                                const Vec2& window) {
  if (s.texture != 0 && s.index == index && s.volume == volume && s.window == window) return;
  const ScalarVolume& v = *volume;
  const auto [u, w] = slice_axes(axis);
  const int nu = v.grid.dims[u], nw = v.grid.dims[w];
  std::vector<std::uint8_t> rgba(std::size_t(4) * nu * nw, 255);
  const double scale = 255.0 / std::max(window[1] - window[0], 1e-12);
  for (int r = 0; r < nw; ++r)
    for (int c = 0; c < nu; ++c) {
      std::array<int, 3> ijk{};
      ijk[axis] = index;
      ijk[u] = c;
      ijk[w] = nw - 1 - r;  // row 0 is the top: the in-plane "up" axis grows upwards
      const double g = std::clamp((v.at(ijk[0], ijk[1], ijk[2]) - window[0]) * scale, 0.0, 255.0);
      for (int k = 0; k < 3; ++k) rgba[4 * (std::size_t(r) * nu + c) + k] = std::uint8_t(g);
    }
  if (s.texture == 0) gl::GenTextures(1, &s.texture);
  gl::BindTexture(GL_TEXTURE_2D, s.texture);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // voxels stay voxels
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, nu, nw, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  s.index = index;
  s.volume = volume;
  s.window = window;
}

const std::vector<Vec3>& SlicePanel::mesh_voxels(const std::shared_ptr<const MeshSnapshot>& shared,
                                                 const VoxelGrid& grid) {
  if (voxels_of_ == shared) return voxels_;
  const MeshSnapshot& mesh = *shared;
  const Mat3 inverse = grid.linear.inverse();
  voxels_.resize(mesh.n_vertices());
  const auto& p = mesh.positions;
  for (std::size_t i = 0; i < voxels_.size(); ++i)
    voxels_[i] = inverse * (Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]) - grid.offset);
  voxels_of_ = shared;
  return voxels_;
}

std::optional<Vec3> SlicePanel::draw(const VolumeImage& image, const Vec3& point,
                                     const std::shared_ptr<const MeshSnapshot>& shared_mesh,
                                     const Vec2& window, float x, float y, float side,
                                     std::vector<WidgetRect>* widgets) {
  if (!image.intensity) return std::nullopt;
  const ScalarVolume& v = *image.intensity;
  const Vec3 spacing = v.grid.spacing();
  const Vec3 p = v.grid.to_voxel(point);
  const std::vector<Vec3>& voxels = mesh_voxels(shared_mesh, v.grid);
  const MeshSnapshot& mesh = *shared_mesh;
  std::optional<Vec3> moved;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("Slices", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  for (int axis : {2, 1, 0}) {
    const auto [u, w] = slice_axes(axis);
    const int index = std::clamp(static_cast<int>(std::lround(p[axis])), 0, v.grid.dims[axis] - 1);
    Slice& s = slices_[axis];
    update_texture(s, axis, index, image.intensity, window);
    // Millimetres keep their proportions: anisotropic voxels are drawn stretched.
    const double width_mm = v.grid.dims[u] * spacing[u], height_mm = v.grid.dims[w] * spacing[w];
    const float k = side / static_cast<float>(std::max(width_mm, height_mm));
    const ImVec2 size(static_cast<float>(width_mm) * k, static_cast<float>(height_mm) * k);
    ImGui::BeginGroup();
    ImGui::Text("%s = %d", kSliceTitles[axis], index);
    const ImVec2 lo = ImGui::GetCursorScreenPos();
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(s.texture)), size);
    const bool clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
    ImGui::EndGroup();
    if (axis != 0) ImGui::SameLine();
    if (widgets)
      widgets->push_back({kSliceNames[axis], lo.x, lo.y, lo.x + size.x, lo.y + size.y, false});
    // Voxel coordinates (centres at integers) to screen: voxel c spans [c - 1/2, c + 1/2].
    const auto to_screen = [&](double cu, double cw) {
      return ImVec2(lo.x + static_cast<float>((cu + 0.5) / v.grid.dims[u]) * size.x,
                    lo.y + size.y - static_cast<float>((cw + 0.5) / v.grid.dims[w]) * size.y);
    };
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->PushClipRect(lo, ImVec2(lo.x + size.x, lo.y + size.y), true);
    // The layer's intersection with the plane: the crossing points of each triangle's edges.
    const ImU32 curve = IM_COL32(255, 200, 40, 255);
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
      ImVec2 ends[3];
      int n = 0;
      for (int e = 0; e < 3; ++e) {
        const Vec3& a = voxels[mesh.triangles[t + e]];
        const Vec3& b = voxels[mesh.triangles[t + (e + 1) % 3]];
        const double da = a[axis] - index, db = b[axis] - index;
        if ((da < 0) == (db < 0)) continue;
        const double f = da / (da - db);
        const Vec3 c = a + f * (b - a);
        if (n < 2) ends[n++] = to_screen(c[u], c[w]);
      }
      if (n == 2) draw->AddLine(ends[0], ends[1], curve, 1.5f);
    }
    const ImVec2 mark = to_screen(p[u], p[w]);
    const ImU32 red = IM_COL32(255, 60, 60, 255);
    draw->AddLine(ImVec2(mark.x - 7, mark.y), ImVec2(mark.x + 7, mark.y), red, 1.5f);
    draw->AddLine(ImVec2(mark.x, mark.y - 7), ImVec2(mark.x, mark.y + 7), red, 1.5f);
    draw->PopClipRect();
    if (clicked) {
      const ImVec2 m = ImGui::GetMousePos();
      Vec3 q = p;
      q[axis] = index;
      q[u] = (m.x - lo.x) / size.x * v.grid.dims[u] - 0.5;
      q[w] = (lo.y + size.y - m.y) / size.y * v.grid.dims[w] - 0.5;
      moved = v.grid.to_world(q);
    }
  }
  ImGui::End();
  return moved;
}

}  // namespace dynamesh
