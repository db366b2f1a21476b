// The formula section as ImGui draws it, without a window or a GPU: keys and characters are
// fed the way a person types them, and what reaches the simulation controls is checked. A
// formula is applied on Enter only when it parses; until then the controls keep the running
// one.
#include <gtest/gtest.h>
#include <imgui.h>

#include <string>

#include "app/viewer/formula_panel.h"

namespace dynamesh {
namespace {

// An ImGui context of its own, with the default font and a key map of our choosing.
class HeadlessPanel {
 public:
  HeadlessPanel() : context_(ImGui::CreateContext()) {
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(kPanelWidth, 900.0f);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the atlas NewFrame needs
    io.KeyMap[ImGuiKey_Tab] = kTab;
    io.KeyMap[ImGuiKey_Enter] = kEnter;
    io.KeyMap[ImGuiKey_A] = kA;
    io.KeyMap[ImGuiKey_Backspace] = kBackspace;
  }
  ~HeadlessPanel() { ImGui::DestroyContext(context_); }
  HeadlessPanel(const HeadlessPanel&) = delete;
  HeadlessPanel& operator=(const HeadlessPanel&) = delete;

  static constexpr int kTab = 1, kEnter = 2, kA = 3, kBackspace = 4;

  // One frame of the panel; true when formula_section changed the controls' text.
  bool frame(ViewerState& state, const PanelInfo& info) {
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImGui::GetIO().DisplaySize);
    ImGui::Begin("dynamesh");
    ImGui::PushItemWidth(150);
    const bool changed = formula_section(state, info);
    ImGui::PopItemWidth();
    ImGui::End();
    ImGui::Render();
    return changed;
  }
  // A key pressed for one frame and released over the next; true if either frame applied.
  bool press(int key, ViewerState& state, const PanelInfo& info, bool ctrl = false) {
    ImGuiIO& io = ImGui::GetIO();
    io.KeyCtrl = ctrl;
    io.KeysDown[key] = true;
    bool changed = frame(state, info);
    io.KeysDown[key] = false;
    io.KeyCtrl = false;
    changed |= frame(state, info);
    return changed;
  }
  bool type(const std::string& text, ViewerState& state, const PanelInfo& info) {
    ImGui::GetIO().AddInputCharactersUTF8(text.c_str());
    return frame(state, info);
  }
  bool editing() const { return ImGui::IsAnyItemActive(); }

 private:
  ImGuiContext* context_;
};

ViewerState expr_state() {
  ViewerState s;
  s.controls.scene = "expr";
  s.controls.scene_text = {{"implicit", "x^2 + y^2 + z^2 - 1"}, {"bounds", "-2,-2,-2,2,2,2"}};
  return s;
}

// Tab into the first field (the formula) and select what it holds, as a person would.
void select_formula(HeadlessPanel& panel, ViewerState& state, const PanelInfo& info) {
  panel.frame(state, info);
  panel.frame(state, info);
  panel.press(HeadlessPanel::kTab, state, info);
  ASSERT_TRUE(panel.editing()) << "Tab did not reach the formula field";
  panel.press(HeadlessPanel::kA, state, info, true);
}

TEST(FormulaPanel, FieldsFollowTheRunningTextUntilEdited) {
  HeadlessPanel panel;
  ViewerState state = expr_state();
  PanelInfo info;
  EXPECT_FALSE(panel.frame(state, info));
  EXPECT_EQ(state.formula.implicit, "x^2 + y^2 + z^2 - 1");
  EXPECT_EQ(state.formula.bounds, "-2,-2,-2,2,2,2");
  // The text changes elsewhere (a reset, the settings): the fields follow.
  state.controls.scene_text = {{"height", "sin(x)"}};
  EXPECT_FALSE(panel.frame(state, info));
  EXPECT_EQ(state.formula.kind, ExprKind::kHeight);
  EXPECT_EQ(state.formula.height, "sin(x)");
}

TEST(FormulaPanel, ABrokenFormulaIsNeverSentAndAGoodOneIsOnEnter) {
  ViewerState state = expr_state();
  const TextOptions running = state.controls.scene_text;
  PanelInfo info;
  {
    HeadlessPanel panel;
    ASSERT_NO_FATAL_FAILURE(select_formula(panel, state, info));
    EXPECT_FALSE(panel.type("x^2 + (y", state, info));
    EXPECT_EQ(state.formula.implicit, "x^2 + (y");  // the draft follows every keystroke
    EXPECT_FALSE(check_formula_draft(state.formula).formula[0].empty());
    EXPECT_EQ(state.controls.scene_text, running);  // the running surface goes on
    EXPECT_FALSE(panel.press(HeadlessPanel::kEnter, state, info));
    EXPECT_EQ(state.controls.scene_text, running);
    EXPECT_EQ(state.formula.implicit, "x^2 + (y");  // kept to be fixed
  }
  {
    HeadlessPanel panel;  // a fresh focus: Tab lands on the formula again
    ASSERT_NO_FATAL_FAILURE(select_formula(panel, state, info));
    EXPECT_FALSE(panel.type("x^2 + (y/2)^2 + z^2 - 1", state, info));
    EXPECT_EQ(state.controls.scene_text, running);  // typing alone sends nothing
    EXPECT_TRUE(panel.press(HeadlessPanel::kEnter, state, info));
    ASSERT_EQ(state.controls.scene_text.size(), 2u);
    EXPECT_EQ(state.controls.scene_text[0],
              (std::pair<std::string, std::string>("implicit", "x^2 + (y/2)^2 + z^2 - 1")));
    EXPECT_FALSE(formula_draft_edited(state.formula));
    // Nothing new to send: further frames change nothing.
    EXPECT_FALSE(panel.frame(state, info));
  }
}

}  // namespace
}  // namespace dynamesh
