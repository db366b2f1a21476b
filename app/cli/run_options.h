// Options of `dynamesh-cli run` and their parsing (DESIGN.md, "Command line").
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/render_style.h"
#include "core/adapt/adapt_options.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {

// Bad input on the command line: reported as one line, exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  std::string scene = "capsule-bend";
  ParameterOverrides params;
  TextOptions scene_text;  // --volume, --implicit, ... for scenes that read text
  double t0 = 0.0, t1 = 1.0;
  bool interval_given = false;  // --t0 or --t1
  // The times the animation visits in order, --steps steps per segment; filled from t0, t1
  // when --keyframes is not given.
  std::vector<double> keyframes;
  int steps = 50;
  AdaptOptions adapt;
  bool threshold_given = false, epsilon_given = false, density_given = false;
  double edge_length = 0.0;  // 0: the scene's own
  std::string stats_path, export_final_path, export_dir, render_dir;
  int export_every = 1;
  int width = 1280, height = 960;
  std::string color = "error";
  double max_seconds = 0.0;       // 0: no wall-time budget
  double max_memory_mb = 4096.0;  // the budgets' memory estimate must stay below
  ColorSettings colors;           // --color-range (and the threshold, set once it is known)
  bool wireframe = true;
  CameraView camera;
  bool quiet = false;
  bool check = false;  // run the mesh invariant check after every step
};

// Parses the words after `run`. Throws UsageError with one line saying what is wrong.
RunOptions parse_run_options(const std::vector<std::string>& args);
// Fills what the user left out with the scene's suggestions (threshold in its units, sample
// density per its unit area; eps = T / 4) and checks the combination.
void apply_scene_defaults(RunOptions& options, const SceneInfo& scene);

std::string run_help();
std::string main_help();

}  // namespace dynamesh
