// The viewer's window: GLFW with an OpenGL 3.3 core context, the renderer's GL functions
// loaded from it, and Dear ImGui set up on it. The window counts input events (so the
// viewer redraws only when something happened) and collects mouse-wheel turns; its
// callbacks are installed before ImGui's, which chain to them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace dynamesh {

class GlfwWindow {
 public:
  // Throws std::runtime_error when there is no display or no OpenGL 3.3 core context.
  GlfwWindow(int width, int height, const std::string& title);
  ~GlfwWindow();
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  // True when a display server can be reached (without creating a window).
  static bool display_available();
  // True for Mesa's llvmpipe / softpipe and the like (GL_RENDERER strings).
  static bool is_software_renderer(const std::string& renderer);
  // GL_RENDERER of the window's context.
  const std::string& renderer() const { return renderer_; }

  GLFWwindow* handle() const { return window_; }
  bool should_close() const;
  glm::ivec2 framebuffer_size() const;
  glm::ivec2 window_size() const;
  glm::ivec2 position() const;
  void set_position(const glm::ivec2& p);

  void poll_events();
  // Sleeps until an event arrives, wake() is called or `timeout` seconds pass.
  void wait_events(double timeout);
  // Wakes wait_events() from any thread.
  static void wake();
  // Input and window events so far (mouse, keys, resizes, exposure).
  std::uint64_t input_events() const { return input_events_; }
  // Mouse-wheel turns since the last call (positive: away from the user).
  double take_scroll();
  // Files and folders dropped onto the window since the last call.
  std::vector<std::string> take_dropped_paths();
  void begin_ui_frame();
  void end_ui_frame();  // renders ImGui's draw data into the bound framebuffer
  void swap();

 private:
  void install_callbacks();

  GLFWwindow* window_ = nullptr;
  std::string renderer_;
  std::uint64_t input_events_ = 0;
  double scroll_ = 0.0;
  std::vector<std::string> dropped_;
};

}  // namespace dynamesh
