// ViewerState: everything a person can set in the viewer, in one struct — the simulation
// controls, the playback, the camera, the drawing style and the window layout. Saved to and
// restored from a small key = value file (the viewer does so at exit and start, in
// settings_path()), reset by assigning ViewerState{}. No parameter lives anywhere else (no
// static locals), so what is on screen can always be saved and reproduced.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/render/camera.h"
#include "app/render/render_style.h"
#include "app/viewer/formula_draft.h"
#include "app/viewer/simulation.h"

namespace dynamesh {

// The adaptation settings whose meaning depends on a scene's units (mri is in millimetres,
// the analytic scenes about one unit across): kept per scene, so each scene opens at the
// settings last used with it, or at its suggestions the first time.
struct SceneSettings {
  double threshold = 0.008, epsilon = 0.002, density = 2000.0, edge_length = 0.0;

  bool operator==(const SceneSettings&) const = default;
};

struct ViewerState {
  // The viewer opens on the sampled error: what the adaptation is about.
  static RenderStyle default_style() {
    RenderStyle s;
    s.mode = ColorMode::kError;
    return s;
  }

  SimulationControls controls;
  // The settings of the scenes not on screen, by name (the one on screen: `controls`).
  std::map<std::string, SceneSettings> scene_settings;
  // The formula panel's fields (scene expr) as typed; what runs is controls.scene_text.
  // Not saved: filled again from the saved scene_text at start (formula_draft.h).
  FormulaDraft formula;
  // Playback: steps evenly spaced from t0 to t1; `time` is the one shown.
  double t0 = 0.0, t1 = 1.0;
  int steps = 100;
  double time = 0.0;
  bool playing = false;
  bool loop = true;
  // View.
  Camera camera;
  RenderStyle style = default_style();
  bool show_panel = true;
  bool show_colorbar = true;
  // Window layout (screen coordinates; x, y < 0: let the window manager place it).
  int window_x = -1, window_y = -1;
  int window_width = 1280, window_height = 800;
  // Output.
  std::string output_dir = ".";  // screenshots and recordings
  int record_fps = 30;

  // --keyframes: the times playback visits in order, `steps` steps per segment, instead of
  // t0 .. t1 (which stay as they were: keyframes are for this session, t0 and t1 are saved).
  // `playhead` counts the steps taken along them. Not saved.
  std::vector<double> keyframes;
  int playhead = 0;
  // The probed point (world mm; issue 14): a click on the layer or in a slice. Not saved:
  // it belongs to the scan on screen.
  std::optional<Vec3> probe;

  double time_step() const { return steps > 0 ? (t1 - t0) / steps : 0.0; }
  // Keyframes: the number of steps along all segments, and the time after `step` of them.
  int keyframe_steps() const;
  double keyframe_time(int step) const;
  // The times the time slider spans: the keyframes' smallest to largest, else t0 .. t1.
  std::pair<double, double> time_range() const;
};

// Switches to `scene`: the current scene's settings go to scene_settings, the new scene's
// come from there or, the first time, from its suggestions (T, density; eps = T/4; its own
// edge length). Parameters and text options of the old scene are dropped.
void switch_scene(ViewerState& state, const std::string& scene);

// Where the viewer keeps its settings between runs: $XDG_CONFIG_HOME/dynamesh/viewer.conf,
// else ~/.config/dynamesh/viewer.conf; empty when neither variable is set.
std::string settings_path();

// Writes the state (creating its directory) as "key = value" lines (atomically). Throws
// std::runtime_error on failure.
void save_viewer_state(const ViewerState& state, const std::string& path);
// Reads a file written by save_viewer_state over `state`: unknown keys are ignored (older or
// newer versions), malformed values (numbers read as strictly as on the command line) are
// skipped and their keys added to `rejected`. Returns false when the file cannot be read.
bool load_viewer_state(ViewerState& state, const std::string& path,
                       std::vector<std::string>* rejected = nullptr);

}  // namespace dynamesh
