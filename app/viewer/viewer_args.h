// The viewer's command line: `dynamesh [--scene NAME] [the CLI's simulation options]
// [--frames N --screenshot FILE.png] [--width W --height H] [--state FILE] [--play]`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/viewer/viewer_state.h"

namespace dynamesh {

struct ViewerArgs {
  ViewerState state;       // defaults with the command line's options applied
  int frames = -1;         // scripted run: play this many steps, then exit
  std::string screenshot;  // scripted run: write the window (panel included) here at the end
  int width = 1280, height = 800;
  std::string state_file;  // restore from / save to (empty: none)
  bool help = false;
};

// Parses argv. Throws std::invalid_argument with one line saying what is wrong.
ViewerArgs parse_viewer_args(const std::vector<std::string>& args);
std::string viewer_usage();

}  // namespace dynamesh
