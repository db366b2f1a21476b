// The viewer's ImGui side panel and colour bar. Widgets edit the ViewerState directly;
// one-off commands (step, screenshot, ...) come back as PanelActions for the app to carry out.
#pragma once

#include <string>

#include "app/render/color_scale.h"
#include "app/viewer/stats_history.h"
#include "app/viewer/viewer_state.h"

namespace dynamesh {

struct PanelActions {
  bool step_forward = false, step_back = false, restart = false;
  bool controls_changed = false;  // a simulation control moved: re-run the current step
  bool fit = false, reset_camera = false;
  bool screenshot = false, toggle_recording = false;
  bool save_state = false, load_state = false, reset_state = false;
};

struct PanelInfo {
  const StatsHistory* history = nullptr;
  StepStatistics last;
  std::string simulation;  // description of what produces the meshes
  std::string status;      // last message (screenshot written, errors...)
  bool busy = false, recording = false;
  float fps = 0.0f;
  bool has_scale = false;
  ColorScale scale;
};

constexpr float kPanelWidth = 330.0f;

PanelActions draw_panel(ViewerState& state, const PanelInfo& info);
// Vertical bar with numbers at the right edge of the window.
void draw_colorbar_window(const ColorScale& scale, float window_width, float window_height);

}  // namespace dynamesh
