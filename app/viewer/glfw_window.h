// The viewer's window: GLFW with an OpenGL 3.3 core context, the renderer's GL functions
// loaded from it, and Dear ImGui set up on it.
#pragma once

#include <string>

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

  GLFWwindow* handle() const { return window_; }
  bool should_close() const;
  glm::ivec2 framebuffer_size() const;
  glm::ivec2 window_size() const;
  void begin_ui_frame();
  void end_ui_frame();  // renders ImGui's draw data into the bound framebuffer
  void swap();

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace dynamesh
