// dynamesh: the interactive viewer (DESIGN.md, "Viewer").
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/viewer/glfw_window.h"
#include "app/viewer/viewer_app.h"

int main(int argc, char** argv) {
  using namespace dynamesh;
  const std::vector<std::string> words(argv + 1, argv + argc);
  ViewerArgs args;
  try {
    // Once over the defaults to learn where the settings live, then over the saved settings:
    // what the command line says wins over what was saved.
    args = parse_viewer_args(words);
    const std::string state_file = state_file_for(args);
    ViewerState saved;
    std::vector<std::string> rejected;
    std::string notice;
    if (!args.fresh && !state_file.empty() && load_viewer_state(saved, state_file, &rejected)) {
      if (!rejected.empty()) {
        // Shown in the panel too; those values keep their defaults.
        std::string keys;
        for (const std::string& k : rejected) keys += (keys.empty() ? "" : ", ") + k;
        notice = "malformed saved values in " + state_file + " were ignored: " + keys;
        std::fprintf(stderr, "dynamesh: %s\n", notice.c_str());
      }
      try {
        args = parse_viewer_args(words, saved);
        args.camera_scene = saved.controls.scene;
        args.camera_text = saved.controls.scene_text;
      } catch (const std::exception& e) {  // the command line was fine over the defaults
        // Shown in the panel too: a broken file must not stop the program from starting.
        notice = "ignoring the saved settings in " + state_file + " (" + e.what() + ")";
        std::fprintf(stderr, "dynamesh: %s\n", notice.c_str());
      }
      args.notice = notice;
    }
    args.state_file = state_file;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dynamesh: %s\n", e.what());
    return 2;
  }
  if (args.version) {
    std::printf("dynamesh %s\n", DYNAMESH_VERSION);
    return 0;
  }
  if (args.help) {
    std::fputs(viewer_usage().c_str(), stdout);
    return 0;
  }
  if (!GlfwWindow::display_available()) {
    std::fprintf(
        stderr,
        "dynamesh: no display (DISPLAY and WAYLAND_DISPLAY are unset). Without a display, "
        "render frames offscreen instead:\n  dynamesh-cli run --scene %s --steps 50 "
        "--render DIR\n(or run the viewer under a virtual display: xvfb-run -a dynamesh)\n",
        args.state.controls.scene.c_str());
    return 2;
  }
  try {
    return run_viewer(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "dynamesh: %s. Without a usable display, render offscreen instead:\n"
                 "  dynamesh-cli run --scene %s --steps 50 --render DIR\n",
                 e.what(), args.state.controls.scene.c_str());
    return 2;
  }
}
