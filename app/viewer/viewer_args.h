// The viewer's command line: `dynamesh [--scene NAME] [the CLI's simulation options]
// [--width W --height H] [--state FILE | --fresh] [--play]`, plus scripted runs for tests and
// measurements (`--frames N`, `--run-for SECONDS`, `--screenshot`, `--record`). The CLI's
// scene text options (--volume, and --implicit, --bounds, ... of the expr scene) are read as
// dynamesh-cli run reads them, so an assets/examples/*.args file serves both.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/viewer/viewer_state.h"

namespace dynamesh {

struct ViewerArgs {
  ViewerState state;  // `base` with the command line's options applied
  // Scripted, deterministic: N frames, one step each (the first shows the initialisation),
  // waiting for each step; then exit.
  int frames = -1;
  // Scripted, free-running for this long, then print frame timing: frames are drawn as in
  // an interactive session (when something changes), the adapter runs on its worker thread
  // (with --play) and is never waited for.
  double run_for = -1.0;
  // With run_for: turn the camera a little every frame, as a person dragging the view would,
  // so frames are drawn continuously (at most 60 per second).
  bool orbit = false;
  std::string screenshot;  // scripted: write the window (panel included) here at the end
  std::string record;      // scripted: record the run to this .mp4 (PNG frames without ffmpeg)
  std::string frame_log;   // scripted: one CSV row per frame (times in ms)
  // Where settings are read at start and written at exit. Interactive runs default to
  // settings_path(); scripted runs use none unless --state is given.
  std::string state_file;
  bool fresh = false;  // start from the defaults, not the saved settings
  // The scene the state's camera was framed for (settings restored), and its text options
  // (a formula): the view is kept for them. Empty: frame the first mesh.
  std::string camera_scene;
  TextOptions camera_text;
  bool help = false;
  // Shown in the panel's status line at start (e.g. that broken saved settings were ignored).
  std::string notice;
  bool version = false;
  // --camera: the view the first mesh is framed with (instead of the saved or default one).
  std::optional<CameraView> camera;

  bool scripted() const { return frames >= 0 || run_for >= 0.0; }
};

// Parses argv over `base` (the saved settings): options given on the command line win.
// Throws std::invalid_argument with one line saying what is wrong.
ViewerArgs parse_viewer_args(const std::vector<std::string>& args, const ViewerState& base = {});
// The settings file to use (empty: none) for these arguments.
std::string state_file_for(const ViewerArgs& args);
std::string viewer_usage();

}  // namespace dynamesh
