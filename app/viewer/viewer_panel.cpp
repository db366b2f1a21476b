#include "app/viewer/viewer_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>

#include "app/render/colorbar_overlay.h"
#include "app/viewer/formula_panel.h"
#include "core/adapt/adapt_options_check.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

ImU32 to_imgui(const glm::vec3& c) {
  return IM_COL32(static_cast<int>(c.r * 255), static_cast<int>(c.g * 255),
                  static_cast<int>(c.b * 255), 255);
}

const ImVec4 kErrorColor(kPanelErrorRgb[0], kPanelErrorRgb[1], kPanelErrorRgb[2], 1.0f);
// A topology event of the shown step (not an error: cyan, not red).
const ImVec4 kEventColor(0.45f, 0.85f, 1.0f, 1.0f);

// Committed on Enter only: a half-typed number (0.0 on the way to 0.0005) must not reach the
// adapter.
constexpr ImGuiInputTextFlags kOnEnter = ImGuiInputTextFlags_EnterReturnsTrue;

// Text option of the scene (a volume file): edited in a buffer, committed on Enter.
bool text_option(SimulationControls& c, const std::string& key) {
  auto it = std::find_if(c.scene_text.begin(), c.scene_text.end(),
                         [&](const auto& kv) { return kv.first == key; });
  char buffer[1024] = {};
  if (it != c.scene_text.end()) std::snprintf(buffer, sizeof buffer, "%s", it->second.c_str());
  if (!ImGui::InputText(key.c_str(), buffer, sizeof buffer, kOnEnter)) return false;
  if (buffer[0] == '\0') {
    if (it != c.scene_text.end()) c.scene_text.erase(it);
  } else if (it == c.scene_text.end()) {
    c.scene_text.emplace_back(key, buffer);
  } else {
    it->second = buffer;
  }
  return true;
}

void note_widget(PanelActions& a, const PanelInfo& info, const char* label);

// The mri scene's scan: a NIfTI file or a DICOM series folder, typed (committed on Enter) or
// dropped on the window. Opening it is the app's (PanelActions::open_path): loaded on the
// worker, and a file that cannot be read leaves the scene on screen as it was.
void scan_path_field(const SimulationControls& c, PanelActions& a, const PanelInfo& info) {
  const auto it = std::find_if(c.scene_text.begin(), c.scene_text.end(),
                               [](const auto& kv) { return kv.first == "volume"; });
  char buffer[1024] = {};
  if (it != c.scene_text.end()) std::snprintf(buffer, sizeof buffer, "%s", it->second.c_str());
  const bool entered = ImGui::InputText("volume", buffer, sizeof buffer, kOnEnter);
  note_widget(a, info, "volume");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        ".nii / .nii.gz file or DICOM series folder; Enter opens it (or drop it "
        "on the window); empty: Colin27");
  if (entered) a.open_path = buffer;  // empty: the default scan
  a.open_requested |= entered;
}

void scene_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  SimulationControls& c = s.controls;
  const std::vector<SceneInfo>& scenes = *info.scenes;
  if (ImGui::BeginCombo("scene", c.scene.c_str())) {
    for (const SceneInfo& scene : scenes) {
      if (ImGui::Selectable(scene.name.c_str(), scene.name == c.scene)) {
        if (scene.name != c.scene) {
          switch_scene(s, scene.name);  // its own T, eps, density, edge length
          a.restart = true;
        }
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", scene.description.c_str());
    }
    ImGui::EndCombo();
  }
  // The running surface knows its parameters best (a scene built from a file may only know
  // them then); before it runs, the catalogue's defaults.
  const std::vector<SurfaceParameter>* parameters = nullptr;
  if (info.running_scene == c.scene) parameters = &info.running_parameters;
  for (const SceneInfo& scene : scenes)
    if (parameters == nullptr && scene.name == c.scene) parameters = &scene.parameters;
  if (parameters != nullptr) {
    for (const SurfaceParameter& p : *parameters) {
      auto it = std::find_if(c.scene_parameters.rbegin(), c.scene_parameters.rend(),
                             [&](const auto& kv) { return kv.first == p.name; });
      float v = static_cast<float>(it != c.scene_parameters.rend() ? it->second : p.value);
      if (ImGui::SliderFloat(p.name.c_str(), &v, static_cast<float>(p.min),
                             static_cast<float>(p.max), "%.4g")) {
        if (it == c.scene_parameters.rend()) {
          c.scene_parameters.emplace_back(p.name, v);
        } else {
          it->second = v;
        }
      }
      // Rebuilding on every frame of a drag would only queue work: on release.
      a.controls_changed |= ImGui::IsItemDeactivatedAfterEdit();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
    }
  }
  if (c.scene == "expr") {
    // Its own section, which shows the errors under the formula.
    a.controls_changed |= formula_section(s, info);
    return;
  }
  for (std::size_t i = 0; i < c.scene_text.size(); ++i) {
    if (c.scene == "mri" && c.scene_text[i].first == "volume") continue;  // the path field below
    a.controls_changed |= text_option(c, std::string(c.scene_text[i].first));
  }
  if (c.scene == "mri") scan_path_field(c, a, info);
  if (!c.scene_parameters.empty() && ImGui::SmallButton("default parameters")) {
    c.scene_parameters.clear();
    a.controls_changed = true;
  }
  if (!info.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", info.error.c_str());
    ImGui::PopStyleColor();
    ImGui::TextDisabled("(showing the last good mesh)");
  }
  if (!info.open_error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", info.open_error.c_str());
    ImGui::PopStyleColor();
    ImGui::TextDisabled("(the previous scene stays)");
  }
}

// The rectangle of the widget just drawn, for a test that drives the panel (widget_report.h):
// the part the mouse acts on (a slider's label beside its frame is not).
void note_widget(PanelActions& a, const PanelInfo& info, const char* label) {
  if (!info.report_widgets) return;
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  a.widgets.push_back({label, lo.x, lo.y, std::min(hi.x, lo.x + ImGui::CalcItemWidth()), hi.y,
                       ImGui::IsItemActive()});
}

// A slider for a setting that spans decades (T, eps, density): logarithmic, committed when
// released (each value of a drag would restart the adaptation), Ctrl-click types a value.
bool log_slider(const char* label, double& value, double lo, double hi, const char* format) {
  ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &lo, &hi, format,
                      ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat);
  return ImGui::IsItemDeactivatedAfterEdit();
}

void adaptation_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Adaptation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  SimulationControls& c = s.controls;
  const SimulationControls before = c;
  // The sliders span two decades either side of the scene's suggestions (its units).
  double suggested_t = 0.008, suggested_density = 2000.0;
  for (const SceneInfo& scene : *info.scenes)
    if (scene.name == c.scene) {
      suggested_t = scene.suggested_threshold;
      suggested_density = scene.suggested_density;
    }
  bool changed =
      log_slider("threshold T", c.threshold, 0.01 * suggested_t, 100 * suggested_t, "%.4g");
  note_widget(a, info, "threshold T");
  // The band keeps its width relative to T (the CLI's default is T/4): T/100 with the old
  // absolute eps would leave no room to weld. The ratio is the one when the slider was
  // grabbed: a typed "0.002" passes through 0, 0., 0.0 and 0.00, which would collapse it.
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID band = ImGui::GetID("band ratio");
  if (ImGui::IsItemActivated() && before.threshold > 0)
    storage->SetFloat(band, static_cast<float>(before.epsilon / before.threshold));
  if (c.threshold != before.threshold && c.threshold > 0)
    c.epsilon = storage->GetFloat(band, 0.25f) * c.threshold;
  changed |= log_slider("epsilon", c.epsilon, 1e-3 * c.threshold, 0.99 * c.threshold, "%.4g");
  note_widget(a, info, "epsilon");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("hysteresis half-width; follows T when T changes");
  changed |=
      log_slider("density", c.density, 0.01 * suggested_density, 100 * suggested_density, "%.4g");
  note_widget(a, info, "density");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("samples per unit area (at least 9 per triangle)");
  const double k_lo = 0.0, k_hi = 10.0;
  ImGui::SliderScalar("curvature sensitivity k", ImGuiDataType_Double, &c.k, &k_lo, &k_hi, "%.3g");
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  note_widget(a, info, "k");
  ImGui::SliderInt("smoothing iters", &c.smooth_iterations, 0, 10);
  const double settled_lo = 0.0, settled_hi = 0.1;
  ImGui::SliderScalar("settled below", ImGuiDataType_Double, &c.smooth_settled, &settled_lo,
                      &settled_hi, "%.3g");
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "leave a vertex in place while its offset from its ring's centroid is below this\n"
        "fraction of the ring's mean edge (0, the paper's: every vertex moves every step)");
  ImGui::InputDouble("edge length", &c.edge_length, 0.01, 0.1, "%.4g", kOnEnter);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("target edge length (sphere: its right half); 0: the scene's own");
  ImGui::InputInt("max triangles", &c.max_triangles, 10000, 100000, kOnEnter);
  int seed = static_cast<int>(c.seed);
  if (ImGui::InputInt("seed", &seed, 1, 10, kOnEnter)) c.seed = static_cast<unsigned>(seed);
  c.threshold = std::max(c.threshold, 1e-9);
  c.epsilon = std::clamp(c.epsilon, 0.0, 0.99 * c.threshold);
  c.density = std::max(c.density, 1.0);
  c.k = std::max(c.k, 0.0);
  c.smooth_settled = std::clamp(c.smooth_settled, 0.0, 0.99);
  c.edge_length = std::max(c.edge_length, 0.0);
  c.max_triangles = std::max(c.max_triangles, kMinTriangleBudget);
  s.style.colors.threshold = c.threshold;
  // Sliders apply when released; the other fields on Enter (they change only then).
  a.controls_changed |= changed || c.smooth_iterations != before.smooth_iterations ||
                        c.edge_length != before.edge_length ||
                        c.max_triangles != before.max_triangles || c.seed != before.seed;
}

void playback_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Button(s.playing ? "Pause" : "Play")) s.playing = !s.playing;
  ImGui::SameLine();
  a.step_back |= ImGui::Button("<");
  ImGui::SameLine();
  a.step_forward |= ImGui::Button(">");
  note_widget(a, info, "step forward");
  ImGui::SameLine();
  a.restart |= ImGui::Button("Restart");
  note_widget(a, info, "Restart");
  ImGui::SameLine();
  ImGui::Checkbox("loop", &s.loop);
  float t = static_cast<float>(s.time);
  const auto [first, last] = s.time_range();
  if (ImGui::SliderFloat("time", &t, static_cast<float>(first), static_cast<float>(last))) {
    s.time = t;
    a.controls_changed = true;
  }
  ImGui::SliderInt("steps t0..t1", &s.steps, 1, 1000);
  ImGui::TextDisabled("step %llu, t = %.4f%s", static_cast<unsigned long long>(info.last.step),
                      info.last.time, info.busy ? "  (computing)" : "");
  if (info.busy && !info.progress.empty()) ImGui::Text("%s", info.progress.c_str());
}

// Window and level of the intensity colours; by default the scan's robust window (1st-99th
// percentile inside the brain), the same for every frame and layer.
void intensity_controls(ColorSettings& colors, const PanelInfo& info) {
  const bool was_auto = colors.intensity_auto;
  ImGui::Checkbox(info.has_scan ? "scan's window (1-99%)" : "auto window", &colors.intensity_auto);
  if (was_auto && !colors.intensity_auto && info.has_scan) {
    // Start adjusting from what is on screen.
    colors.intensity_window = info.scan_window[1] - info.scan_window[0];
    colors.intensity_level = 0.5 * (info.scan_window[0] + info.scan_window[1]);
  }
  if (!colors.intensity_auto) {
    const double span = info.has_scan ? std::max(info.scan_window[1] - info.scan_window[0], 1.0)
                                      : std::max(colors.intensity_window, 1.0);
    const double w_lo = 0.01 * span, w_hi = 4.0 * span;
    const double l_lo = (info.has_scan ? info.scan_window[0] : colors.intensity_level) - span,
                 l_hi = (info.has_scan ? info.scan_window[1] : colors.intensity_level) + span;
    ImGui::SliderScalar("window", ImGuiDataType_Double, &colors.intensity_window, &w_lo, &w_hi,
                        "%.1f");
    ImGui::SliderScalar("level", ImGuiDataType_Double, &colors.intensity_level, &l_lo, &l_hi,
                        "%.1f");
  }
  ImGui::Checkbox("viridis", &colors.intensity_viridis);
}

// What the scan says at the probed point (a click on the layer or in a slice).
void probe_lines(const VolumeProbe& p) {
  ImGui::Separator();
  ImGui::Text("point  %.1f, %.1f, %.1f mm", p.position.x(), p.position.y(), p.position.z());
  if (p.inside)
    ImGui::Text("voxel  %d, %d, %d", p.index[0], p.index[1], p.index[2]);
  else
    ImGui::TextDisabled("outside the volume");
  ImGui::Text("intensity %.1f   layer depth %.1f mm", p.intensity, p.depth);
  if (!p.region_name.empty()) ImGui::Text("region %s (%d)", p.region_name.c_str(), p.region);
  ImGui::TextDisabled("click the layer or a slice to move the point");
}

void coloring_section(ViewerState& s, PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderStyle& st = s.style;
  if (ImGui::BeginCombo("colour (C)", std::string(color_mode_label(st.mode)).c_str())) {
    for (ColorMode m : kAllColorModes) {
      if (ImGui::Selectable(std::string(color_mode_label(m)).c_str(), m == st.mode)) st.mode = m;
    }
    ImGui::EndCombo();
  }
  if (st.mode == ColorMode::kError) ImGui::Checkbox("viridis", &st.colors.error_viridis);
  if (st.mode == ColorMode::kCurvature || st.mode == ColorMode::kLevel ||
      st.mode == ColorMode::kIntensity) {
    // Fixed ranges keep a video from flickering as the field's values move.
    static constexpr const char* kRanges[] = {"each frame", "first frame", "whole run", "fixed"};
    int range = static_cast<int>(st.colors.range);
    if (ImGui::Combo("range", &range, kRanges, 4)) st.colors.range = static_cast<ColorRange>(range);
    if (st.colors.range == ColorRange::kFixed) {
      ImGui::InputDouble("min", &st.colors.range_min, 0.0, 0.0, "%.4g");
      ImGui::InputDouble("max", &st.colors.range_max, 0.0, 0.0, "%.4g");
      if (!(st.colors.range_max > st.colors.range_min))
        st.colors.range_max = st.colors.range_min + 1e-6;
    }
  }
  if (st.mode == ColorMode::kIntensity) intensity_controls(st.colors, info);
  if (info.probe != nullptr)
    probe_lines(*info.probe);
  else if (info.has_scan)
    ImGui::TextDisabled("click the layer: position, intensity, region");
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

void plot(const char* label, const std::vector<float>& values, const char* format,
          float min = FLT_MAX) {
  if (values.empty()) return;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, format, static_cast<double>(values.back()));
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, min, FLT_MAX,
                   ImVec2(0, 42));
}

// Thousands separated, for triangle and vertex counts.
std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

void statistics_section(const ViewerState& state, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const StepStats& s = info.last;
  ImGui::Text("triangles %s   vertices %s", grouped(s.triangles).c_str(),
              grouped(s.vertices).c_str());
  const double kept = s.vertices > 0 ? 100.0 * double(s.vertices_kept) / double(s.vertices) : 0.0;
  ImGui::Text("splits %s   welds %s   kept %s (%.1f%%)", grouped(s.splits).c_str(),
              grouped(s.welds).c_str(), grouped(s.vertices_kept).c_str(), kept);
  const double bound = state.controls.threshold + state.controls.epsilon;
  const bool over = s.max_error > bound * (1.0 + 1e-9);
  ImGui::Text("max error");
  ImGui::SameLine();
  ImGui::TextColored(over ? kErrorColor : ImGui::GetStyle().Colors[ImGuiCol_Text], "%.3g",
                     s.max_error);
  ImGui::SameLine();
  ImGui::TextDisabled("(T+eps %.3g)", bound);
  ImGui::Text("mean error %.3g", s.mean_error);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("over all samples, after the step");
  if (s.budget_hit) ImGui::TextColored(kErrorColor, "triangle budget hit: refinement stopped");
  if (s.projection_failures > 0)
    ImGui::TextColored(kErrorColor, "%zu projections did not converge", s.projection_failures);
  // Time per phase, as bars sharing the step's total.
  const PhaseSeconds& p = s.seconds;
  ImGui::Text("step %.1f ms   %.0f fps", 1e3 * p.total, static_cast<double>(info.fps));
  const std::pair<const char*, double> phases[] = {
      {"project", p.project}, {"smooth", p.smooth}, {"sample", p.sample},
      {"weld", p.weld},       {"split", p.split},   {"renumber", p.renumber}};
  for (const auto& [name, seconds] : phases) {
    char overlay[48];
    std::snprintf(overlay, sizeof overlay, "%s %.1f ms", name, 1e3 * seconds);
    ImGui::ProgressBar(p.total > 0 ? static_cast<float>(seconds / p.total) : 0.0f,
                       ImVec2(-FLT_MIN, 0), overlay);
  }
  // Topology events (issue 16): a merge is just another frame, but the panel says it happened
  // and how the mesh followed; this step's in colour, the run's earlier ones greyed.
  if (info.history != nullptr && !info.history->topology_events().empty()) {
    const std::vector<std::string> now = StatsHistory::topology_notes(s);
    for (const std::string& note : info.history->topology_events()) {
      if (std::find(now.begin(), now.end(), note) != now.end())
        ImGui::TextColored(kEventColor, "topology: %s", note.c_str());
      else
        ImGui::TextDisabled("topology: %s", note.c_str());
    }
  }
  if (info.history != nullptr && info.history->size() > 1) {
    const StatsHistory::Series& h = info.history->series();
    ImGui::TextDisabled("last %zu steps", info.history->size());
    plot("triangles", h.triangles, "%.0f", 0.0f);
    plot("max error", h.max_error, "%.3g", 0.0f);
    plot("mean error", h.mean_error, "%.3g", 0.0f);
    plot("splits", h.splits, "%.0f", 0.0f);
    plot("welds", h.welds, "%.0f", 0.0f);
    plot("kept %", h.kept_percent, "%.1f");
    plot("step ms", h.step_ms, "%.1f", 0.0f);
  }
}

void output_section(PanelActions& a, const PanelInfo& info) {
  if (!ImGui::CollapsingHeader("Output", ImGuiTreeNodeFlags_DefaultOpen)) return;
  a.screenshot |= ImGui::Button("Screenshot (P)");
  ImGui::SameLine();
  a.toggle_recording |=
      ImGui::Button(info.recorded_frames >= 0 ? "Stop recording (R)" : "Record (R)");
  if (info.recorded_frames >= 0) {
    ImGui::TextColored(kErrorColor, "recording: %d frames (one per step; play to record)",
                       info.recorded_frames);
  }
  a.save_settings |= ImGui::Button("Save settings");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("%s", info.settings.empty()
                                ? "no settings file (scripted run)"
                                : ("saved at exit too, in " + info.settings).c_str());
  }
  ImGui::SameLine();
  a.reset_settings |= ImGui::Button("Reset to defaults");
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
  scene_section(state, actions, info);
  adaptation_section(state, actions, info);
  playback_section(state, actions, info);
  coloring_section(state, actions, info);
  statistics_section(state, info);
  output_section(actions, info);
  ImGui::PopItemWidth();
  ImGui::End();
  return actions;
}

void draw_colorbar_window(const ColorScale& scale, float window_width, float window_height) {
  const float bar_w = 22.0f, bar_h = std::min(320.0f, 0.5f * window_height);
  const float x0 = window_width - bar_w - 24.0f, y0 = 0.5f * (window_height - bar_h);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  // A light card behind bar and numbers keeps them readable over the surface.
  const float card_w = kColorbarWidth - 4.0f;
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
    // At least one and a half lines apart: a deep mesh's levels are thinned.
    const float line = ImGui::GetTextLineHeight();
    for (int v : discrete_labels(scale, static_cast<int>(bar_h / (1.5f * line)))) label(v);
  } else {
    for (double f : {0.0, 0.25, 0.5, 0.75, 1.0}) label(scale.min + f * (scale.max - scale.min));
  }
  const ImVec2 size = ImGui::CalcTextSize(scale.label.c_str());
  draw->AddText(ImVec2(window_width - 10 - size.x, y0 - 10 - size.y), text, scale.label.c_str());
}

}  // namespace dynamesh
