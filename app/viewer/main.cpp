// dynamesh: the interactive viewer (DESIGN.md, "Viewer").
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/viewer/glfw_window.h"
#include "app/viewer/viewer_app.h"

int main(int argc, char** argv) {
  using namespace dynamesh;
  ViewerArgs args;
  try {
    args = parse_viewer_args(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dynamesh: %s\n", e.what());
    return 2;
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
