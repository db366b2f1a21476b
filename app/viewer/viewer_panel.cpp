#include "app/viewer/viewer_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app/render/colorbar_overlay.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

ImU32 to_imgui(const glm::vec3& c) {
  return IM_COL32(static_cast<int>(c.r * 255), static_cast<int>(c.g * 255),
                  static_cast<int>(c.b * 255), 255);
}

void scene_section(ViewerState& s, PanelActions& a) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const std::vector<SceneInfo> scenes = list_scenes();
  if (ImGui::BeginCombo("scene", s.controls.scene.c_str())) {
    for (const SceneInfo& info : scenes) {
      if (ImGui::Selectable(info.name.c_str(), info.name == s.controls.scene)) {
        s.controls.scene = info.name;
        s.controls.scene_parameters.clear();
        a.restart = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info.description.c_str());
    }
    ImGui::EndCombo();
  }
  for (const SceneInfo& info : scenes) {
    if (info.name != s.controls.scene) continue;
    for (const SurfaceParameter& p : info.parameters) {
      auto it = std::find_if(s.controls.scene_parameters.begin(), s.controls.scene_parameters.end(),
                             [&](const auto& kv) { return kv.first == p.name; });
      float v = static_cast<float>(it != s.controls.scene_parameters.end() ? it->second : p.value);
      if (ImGui::SliderFloat(p.name.c_str(), &v, static_cast<float>(p.min),
                             static_cast<float>(p.max))) {
        if (it == s.controls.scene_parameters.end()) {
          s.controls.scene_parameters.emplace_back(p.name, v);
        } else {
          it->second = v;
        }
        a.restart = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
    }
  }
}

void adaptation_section(ViewerState& s, PanelActions& a) {
  if (!ImGui::CollapsingHeader("Adaptation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  SimulationControls& c = s.controls;
  bool changed = false;
  changed |= ImGui::InputDouble("threshold T", &c.threshold, 0.001, 0.01, "%.5f");
  changed |= ImGui::InputDouble("epsilon", &c.epsilon, 0.0001, 0.001, "%.5f");
  changed |= ImGui::InputDouble("density", &c.density, 100, 1000, "%.0f");
  changed |= ImGui::InputDouble("stiffness k", &c.k, 0.5, 1.0, "%.2f");
  changed |= ImGui::SliderInt("smoothing iters", &c.smooth_iterations, 0, 10);
  changed |= ImGui::InputInt("max triangles", &c.max_triangles, 10000, 100000);
  c.threshold = std::max(c.threshold, 1e-9);
  c.epsilon = std::clamp(c.epsilon, 0.0, 0.99 * c.threshold);
  c.density = std::max(c.density, 1.0);
  c.max_triangles = std::max(c.max_triangles, 8);
  s.style.colors.threshold = c.threshold;
  a.controls_changed |= changed;
}

void playback_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Button(s.playing ? "Pause" : "Play")) s.playing = !s.playing;
  ImGui::SameLine();
  a.step_back |= ImGui::Button("<");
  ImGui::SameLine();
  a.step_forward |= ImGui::Button(">");
  ImGui::SameLine();
  a.restart |= ImGui::Button("Restart");
  ImGui::SameLine();
  ImGui::Checkbox("loop", &s.loop);
  float t = static_cast<float>(s.time);
  if (ImGui::SliderFloat("time", &t, static_cast<float>(s.t0), static_cast<float>(s.t1))) {
    s.time = t;
    a.controls_changed = true;
  }
  ImGui::SliderInt("steps t0..t1", &s.steps, 1, 1000);
  ImGui::TextDisabled("%s%s", info.simulation.c_str(), info.busy ? "  (computing)" : "");
}

void coloring_section(ViewerState& s, PanelActions& a) {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderStyle& st = s.style;
  if (ImGui::BeginCombo("colour", std::string(color_mode_label(st.mode)).c_str())) {
    for (ColorMode m : kAllColorModes) {
      if (ImGui::Selectable(std::string(color_mode_label(m)).c_str(), m == st.mode)) st.mode = m;
    }
    ImGui::EndCombo();
  }
  if (st.mode == ColorMode::kError) ImGui::Checkbox("viridis", &st.colors.error_viridis);
  if (st.mode == ColorMode::kIntensity) {
    ImGui::Checkbox("auto window", &st.colors.intensity_auto);
    if (!st.colors.intensity_auto) {
      ImGui::InputDouble("window", &st.colors.intensity_window, 1.0, 10.0, "%.1f");
      ImGui::InputDouble("level", &st.colors.intensity_level, 1.0, 10.0, "%.1f");
    }
  }
  ImGui::Checkbox("wireframe (W)", &st.wireframe);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::SliderFloat("width", &st.wire_width, 0.5f, 4.0f, "%.1f px");
  ImGui::Checkbox("colour bar", &s.show_colorbar);
  ImGui::SameLine();
  ImGui::Checkbox("common size", &s.camera.normalize_size);
  a.fit |= ImGui::Button("Fit (F)");
  ImGui::SameLine();
  a.reset_camera |= ImGui::Button("Reset view");
}

void plot(const char* label, const std::vector<float>& values, const char* format) {
  if (values.empty()) return;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, format, values.back());
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, FLT_MAX,
                   FLT_MAX, ImVec2(0, 50));
}

void statistics_section(const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const StepStatistics& s = info.last;
  ImGui::Text("triangles %zu   vertices %zu", s.triangles, s.vertices);
  ImGui::Text("max error %.3g   mean %.3g", s.max_error, s.mean_error);
  ImGui::Text("splits %zu  welds %zu  step %.1f ms", s.splits, s.welds, 1e3 * s.seconds);
  ImGui::Text("%.0f fps", info.fps);
  if (s.budget_hit) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "triangle budget hit");
  if (info.history != nullptr) {
    plot("triangles", info.history->triangles, "%.0f");
    plot("max error", info.history->max_error, "%.3g");
    plot("step ms", info.history->step_ms, "%.1f");
  }
}

void output_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Output", ImGuiTreeNodeFlags_DefaultOpen)) return;
  a.screenshot |= ImGui::Button("Screenshot (P)");
  ImGui::SameLine();
  a.toggle_recording |= ImGui::Button(info.recording ? "Stop recording (R)" : "Record (R)");
  a.save_state |= ImGui::Button("Save state");
  ImGui::SameLine();
  a.load_state |= ImGui::Button("Load state");
  ImGui::SameLine();
  a.reset_state |= ImGui::Button("Reset all");
  (void)s;
  if (!info.status.empty()) ImGui::TextWrapped("%s", info.status.c_str());
}

}  // namespace

PanelActions draw_panel(ViewerState& state, const PanelInfo& info) {
  PanelActions actions;
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, ImGui::GetIO().DisplaySize.y));
  ImGui::Begin("dynamesh", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::PushItemWidth(150);
  scene_section(state, actions);
  adaptation_section(state, actions);
  playback_section(state, actions, info);
  coloring_section(state, actions);
  statistics_section(info);
  output_section(state, actions, info);
  ImGui::PopItemWidth();
  ImGui::End();
  return actions;
}

void draw_colorbar_window(const ColorScale& scale, float window_width, float window_height) {
  const float bar_w = 22.0f, bar_h = std::min(320.0f, 0.5f * window_height);
  const float x0 = window_width - bar_w - 24.0f, y0 = 0.5f * (window_height - bar_h);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  // A light card behind bar and numbers keeps them readable over the surface.
  const float card_w = std::max(ImGui::CalcTextSize(scale.label.c_str()).x + 20.0f, 110.0f);
  draw->AddRectFilled(ImVec2(window_width - card_w, y0 - 36.0f),
                      ImVec2(window_width - 4.0f, y0 + bar_h + 16.0f), IM_COL32(245, 246, 248, 225),
                      6.0f);
  const Colormap& map = colormap(scale.map);
  constexpr int kSegments = 64;
  for (int i = 0; i < kSegments; ++i) {
    const float a = static_cast<float>(i) / kSegments, b = static_cast<float>(i + 1) / kSegments;
    const ImU32 top = to_imgui(map.sample(1.0f - a)), bottom = to_imgui(map.sample(1.0f - b));
    draw->AddRectFilledMultiColor(ImVec2(x0, y0 + a * bar_h), ImVec2(x0 + bar_w, y0 + b * bar_h),
                                  top, top, bottom, bottom);
  }
  draw->AddRect(ImVec2(x0, y0), ImVec2(x0 + bar_w, y0 + bar_h), IM_COL32(40, 40, 40, 255));
  const ImU32 text = IM_COL32(20, 20, 25, 255);
  const auto label = [&](double v) {
    const std::string t = colorbar_label(v);
    const float y = y0 + static_cast<float>((scale.max - v) / (scale.max - scale.min)) * bar_h;
    const ImVec2 size = ImGui::CalcTextSize(t.c_str());
    draw->AddText(ImVec2(x0 - 6 - size.x, y - 0.5f * size.y), text, t.c_str());
  };
  if (scale.discrete) {
    for (int v = static_cast<int>(scale.min + 0.5f); v <= scale.max; ++v) label(v);
  } else {
    for (double f : {0.0, 0.25, 0.5, 0.75, 1.0}) label(scale.min + f * (scale.max - scale.min));
  }
  const ImVec2 size = ImGui::CalcTextSize(scale.label.c_str());
  draw->AddText(ImVec2(window_width - 10 - size.x, y0 - 10 - size.y), text, scale.label.c_str());
}

}  // namespace dynamesh
