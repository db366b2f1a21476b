#include "app/viewer/formula_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <filesystem>

#include "app/viewer/formula_draft.h"

namespace dynamesh {
namespace {

const ImVec4 kErrorColor(kPanelErrorRgb[0], kPanelErrorRgb[1], kPanelErrorRgb[2], 1.0f);

// Enter applies (what a person typing a formula and wanting to see it expects); Ctrl+Enter
// breaks a long formula into lines.
constexpr ImGuiInputTextFlags kFormulaFlags =
    ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CtrlEnterForNewLine;
constexpr ImGuiInputTextFlags kFieldFlags = ImGuiInputTextFlags_EnterReturnsTrue;

constexpr const char* kKindLabels[] = {"implicit F(x,y,z,t) = 0", "height field y = f(x,z,t)",
                                       "parametric X,Y,Z (u,v,t)"};

void error_line(const std::string& message) {
  if (message.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextWrapped("%s", message.c_str());
  ImGui::PopStyleColor();
}

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// Characters per line of a full-width formula field (the font is monospaced): formulas filled
// in from elsewhere are wrapped to it, so they show whole without scrolling sideways.
std::size_t formula_columns() {
  const ImGuiStyle& style = ImGui::GetStyle();
  const float width =
      ImGui::GetContentRegionAvail().x - 2.0f * style.FramePadding.x - style.ScrollbarSize;
  const float glyph = ImGui::CalcTextSize("m").x;
  return glyph > 0.0f ? static_cast<std::size_t>(std::max(16.0f, width / glyph)) : 40;
}

// Full width, as tall as the formula's lines (2 to 6). True on Enter.
bool formula_field(const char* id, std::string& text) {
  const int lines =
      std::clamp(static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1, 2, 6);
  const float height = static_cast<float>(lines) * ImGui::GetTextLineHeight() +
                       2.0f * ImGui::GetStyle().FramePadding.y;
  return ImGui::InputTextMultiline(id, &text, ImVec2(-FLT_MIN, height), kFormulaFlags);
}

// What building the applied formula found: it concerns the formula, so it goes under it.
// When the fields are the applied ones and their own checks fail, those say it already.
void build_error(const PanelInfo& info, const FormulaDraft& d, const FormulaCheck& check) {
  if (info.error.empty()) return;
  if (check.ok() || formula_draft_edited(d)) error_line(info.error);
  ImGui::TextDisabled(info.running_scene.empty() ? "(no mesh yet)"
                                                 : "(showing the last good mesh)");
}

std::string example_label(const FormulaExample& e) {
  std::string label = e.name;
  std::replace(label.begin(), label.end(), '-', ' ');
  return label;
}

// The text with its base mesh as an absolute path: an example names it so, a command line
// given from the repository root relative to it.
TextOptions comparable(TextOptions text) {
  for (auto& [key, value] : text)
    if (key == "base-mesh") {
      std::error_code error;  // no working directory: compared as written
      const std::filesystem::path path = std::filesystem::absolute(value, error);
      if (!error) value = path.lexically_normal().string();
    }
  return text;
}

// The example whose surface the fields describe, if any.
const FormulaExample* shown_example(const std::vector<FormulaExample>& examples,
                                    const FormulaDraft& draft) {
  const TextOptions shown = comparable(formula_draft_text(draft));
  for (const FormulaExample& e : examples) {
    if (e.error.empty() && comparable(formula_draft_text(formula_draft_from_text(e.text))) == shown)
      return &e;
  }
  return nullptr;
}

// The library; true when one was picked (and loaded into the fields).
bool example_combo(FormulaDraft& d, const PanelInfo& info, std::size_t columns) {
  if (info.examples == nullptr || info.examples->empty()) {
    ImGui::TextDisabled("no examples found (DYNAMESH_ASSETS=DIR names assets/)");
    return false;
  }
  const FormulaExample* shown = shown_example(*info.examples, d);
  bool picked = false;
  if (ImGui::BeginCombo("example", shown ? example_label(*shown).c_str() : "(choose one)")) {
    for (const FormulaExample& e : *info.examples) {
      if (!e.error.empty()) {
        ImGui::TextDisabled("%s", example_label(e).c_str());
        tooltip(e.error.c_str());
        continue;
      }
      if (ImGui::Selectable(example_label(e).c_str(), &e == shown)) {
        const std::optional<TextOptions> running = d.source;
        d = formula_draft_from_text(e.text, columns);
        d.source = running;  // loaded, not yet applied
        picked = true;
      }
      std::string text;
      for (const auto& [key, value] : e.text) text += "--" + key + " " + value + "\n";
      tooltip(text.c_str());
    }
    ImGui::EndCombo();
  }
  tooltip("examples from assets/examples/*.args: picking one runs it");
  return picked;
}

// The kind's fields; true on Enter in one of them.
bool kind_fields(FormulaDraft& d, const FormulaCheck& check, const PanelInfo& info) {
  bool enter = false;
  switch (d.kind) {
    case ExprKind::kImplicit:
      ImGui::TextUnformatted("F(x, y, z, t) = 0, F < 0 inside");
      enter |= formula_field("##implicit", d.implicit);
      error_line(check.formula[0]);
      build_error(info, d, check);
      enter |= ImGui::InputText("bounds", &d.bounds, kFieldFlags);
      tooltip("xmin,ymin,zmin,xmax,ymax,zmax: a box around the surface (F > 0 on its sides)");
      error_line(check.extent);
      enter |= ImGui::InputTextWithHint("base mesh", "none: a box, sphere topology", &d.base_mesh,
                                        kFieldFlags);
      tooltip(d.base_mesh.empty()
                  ? "an OBJ or PLY triangle mesh near the surface: any genus (e.g. torus.obj)"
                  : d.base_mesh.c_str());
      error_line(check.base_mesh);
      break;
    case ExprKind::kHeight:
      ImGui::TextUnformatted("y = f(x, z, t)");
      enter |= formula_field("##height", d.height);
      error_line(check.formula[0]);
      build_error(info, d, check);
      enter |= ImGui::InputTextWithHint("domain", "-1,1,-1,1", &d.height_domain, kFieldFlags);
      tooltip("xmin,xmax,zmin,zmax (entries may be formulas such as 2*pi)");
      error_line(check.extent);
      break;
    case ExprKind::kParametric: {
      constexpr const char* kLabels[] = {"X(u, v, t)", "Y(u, v, t)", "Z(u, v, t)"};
      constexpr const char* kIds[] = {"##X", "##Y", "##Z"};
      for (int i = 0; i < 3; ++i) {
        ImGui::TextUnformatted(kLabels[i]);
        enter |= formula_field(kIds[i], d.parametric[i]);
        error_line(check.formula[i]);
      }
      build_error(info, d, check);
      enter |= ImGui::InputText("domain", &d.parametric_domain, kFieldFlags);
      tooltip("umin,umax,vmin,vmax (entries may be formulas such as 2*pi)");
      error_line(check.extent);
      ImGui::Checkbox("periodic in u", &d.periodic_u);
      ImGui::SameLine();
      ImGui::Checkbox("in v", &d.periodic_v);
      tooltip("a periodic direction must close up exactly: use 2*pi, not 6.28");
      break;
    }
  }
  return enter;
}

}  // namespace

bool formula_section(ViewerState& state, const PanelInfo& info) {
  SimulationControls& c = state.controls;
  FormulaDraft& d = state.formula;
  const std::size_t columns = formula_columns();
  // The text changed behind the panel's back (command line, settings, another scene).
  if (d.source != c.scene_text) d = formula_draft_from_text(c.scene_text, columns);

  ImGui::PushItemWidth(-80.0f);  // room for the labels at the right
  bool apply = example_combo(d, info, columns);
  int kind = static_cast<int>(d.kind);
  if (ImGui::Combo("kind", &kind, kKindLabels, IM_ARRAYSIZE(kKindLabels)))
    d.kind = static_cast<ExprKind>(kind);
  // Parsed on every frame drawn: a few muparser parses, far below a frame's time, and
  // never stale.
  const FormulaCheck check = check_formula_draft(d);
  apply |= kind_fields(d, check, info);
  error_line(check.options);
  ImGui::PopItemWidth();

  const bool edited = formula_draft_edited(d);
  ImGui::BeginDisabled(!check.ok() || !edited);
  apply |= ImGui::Button("Apply");
  ImGui::EndDisabled();
  tooltip("build this surface (Enter in a field does too); Ctrl+Enter breaks a formula's line");
  ImGui::SameLine();
  // After a failed build the mesh on screen is the last good formula's: back to it.
  const bool failed_elsewhere = info.running_scene == "expr" && info.running_text != c.scene_text;
  ImGui::BeginDisabled(!edited && !failed_elsewhere);
  const bool revert = ImGui::Button("Revert");
  ImGui::EndDisabled();
  tooltip("the fields back to the surface on screen");
  const char* status = info.busy     ? "(computing)"
                       : !check.ok() ? "fix the red lines to apply"
                       : edited      ? "edited: Enter applies"
                                     : nullptr;
  if (status != nullptr) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s", status);
  }

  bool changed = false;
  if (revert) {
    if (failed_elsewhere) {
      c.scene_text = info.running_text;
      changed = true;
    }
    d = formula_draft_from_text(c.scene_text, columns);
  } else if (apply && check.ok()) {
    const TextOptions text = formula_draft_text(d);
    d.source = text;
    changed = text != c.scene_text;
    c.scene_text = text;
  }
  return changed;
}

}  // namespace dynamesh
