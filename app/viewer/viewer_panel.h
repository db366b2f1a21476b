// The viewer's ImGui side panel and colour bar. Widgets edit the ViewerState directly;
// one-off commands (step, screenshot, ...) come back as PanelActions for the app to carry out.
#pragma once

#include <string>
#include <vector>

#include "app/render/color_scale.h"
#include "app/viewer/formula_examples.h"
#include "app/viewer/stats_history.h"
#include "app/viewer/viewer_state.h"
#include "app/viewer/volume_probe.h"
#include "app/viewer/widget_report.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {

struct PanelActions {
  bool step_forward = false, step_back = false;
  bool restart = false;           // re-initialise at t0
  bool controls_changed = false;  // a simulation control moved: re-run at the current time
  bool fit = false, reset_camera = false;
  bool screenshot = false, toggle_recording = false;
  bool save_settings = false, reset_settings = false;
  // The scan path field was committed (Enter): open this scan (empty: the scene's default).
  bool open_requested = false;
  std::string open_path;
  std::vector<WidgetRect> widgets;  // where the sliders are, when PanelInfo::report_widgets
};

struct PanelInfo {
  const std::vector<SceneInfo>* scenes = nullptr;  // the catalogue
  // The parameters of the scene the adapter runs on (values and ranges), and its name.
  std::string running_scene;
  std::vector<SurfaceParameter> running_parameters;
  TextOptions running_text;  // its text options: the formula of the mesh on screen
  const std::vector<FormulaExample>* examples = nullptr;  // the formula panel's library
  const StatsHistory* history = nullptr;
  StepStats last;          // the adapter's last step
  std::string error;       // the last request failed: shown in red
  std::string open_error;  // the last scan opened could not be loaded: shown in red
  std::string status;      // last message (screenshot written...)
  std::string settings;    // the settings file (empty: none)
  bool busy = false;
  int recorded_frames = -1;  // >= 0 while recording
  float fps = 0.0f;
  bool has_scale = false;
  ColorScale scale;
  bool report_widgets = false;  // a test asked where the widgets are (widget_report.h)
  // The scan on screen (mri): its robust window, and the probed point when there is one.
  bool has_scan = false;
  Vec2 scan_window{Vec2::Zero()};
  const VolumeProbe* probe = nullptr;
  std::string progress;  // loading a scan: stage and percentage, while busy
};

constexpr float kPanelWidth = 340.0f;
// Errors and warnings in the panel (red, readable on ImGui's dark theme).
constexpr float kPanelErrorRgb[3] = {1.0f, 0.42f, 0.35f};
// The colour bar's card at the right edge: the 3D view is laid out beside it, not under it.
constexpr float kColorbarWidth = 130.0f;

PanelActions draw_panel(ViewerState& state, const PanelInfo& info);
// Vertical bar with numbers at the right edge of the window.
void draw_colorbar_window(const ColorScale& scale, float window_width, float window_height);

}  // namespace dynamesh
