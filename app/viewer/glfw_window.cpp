#include "app/viewer/glfw_window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "app/render/gl_api.h"
#include "app/render/gl_loader.h"

namespace dynamesh {

bool GlfwWindow::display_available() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

GlfwWindow::GlfwWindow(int width, int height, const std::string& title) {
  if (!display_available() || glfwInit() != GLFW_TRUE) {
    throw std::runtime_error("no display available");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // No multisampling here: the 3D view is drawn into its own (multisampled where that is
  // cheap) target and copied in; the panel does its own antialiasing.
  glfwWindowHint(GLFW_SAMPLES, 0);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    glfwTerminate();
    throw std::runtime_error("cannot open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(window_);
  const std::string missing = gl::load_functions(
      [](const char* name) { return reinterpret_cast<gl::ProcAddress>(glfwGetProcAddress(name)); });
  if (!missing.empty()) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw std::runtime_error("OpenGL functions missing: " + missing);
  }
  renderer_ = reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
  glfwSwapInterval(1);
  install_callbacks();  // before ImGui's, which call the ones they replace
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // layout is not state: ViewerState is
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

GlfwWindow::~GlfwWindow() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool GlfwWindow::should_close() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

glm::ivec2 GlfwWindow::framebuffer_size() const {
  glm::ivec2 s;
  glfwGetFramebufferSize(window_, &s.x, &s.y);
  return s;
}

glm::ivec2 GlfwWindow::window_size() const {
  glm::ivec2 s;
  glfwGetWindowSize(window_, &s.x, &s.y);
  return s;
}

bool GlfwWindow::is_software_renderer(const std::string& renderer) {
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "SWR", "Software"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

void GlfwWindow::install_callbacks() {
  glfwSetWindowUserPointer(window_, this);
  static constexpr auto self = [](GLFWwindow* w) {
    return static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
  };
  static constexpr auto count = [](GLFWwindow* w) { ++self(w)->input_events_; };
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double, double) { count(w); });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int, int, int) { count(w); });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    count(w);
    self(w)->scroll_ += dy;
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int, int, int, int) { count(w); });
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned) { count(w); });
  glfwSetDropCallback(window_, [](GLFWwindow* w, int n, const char** paths) {
    count(w);
    for (int i = 0; i < n; ++i) self(w)->dropped_.emplace_back(paths[i]);
  });
  glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int) { count(w); });
  glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int) { count(w); });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { count(w); });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { count(w); });
}

glm::ivec2 GlfwWindow::position() const {
  glm::ivec2 p;
  glfwGetWindowPos(window_, &p.x, &p.y);
  return p;
}

void GlfwWindow::set_position(const glm::ivec2& p) {
  glfwSetWindowPos(window_, p.x, p.y);
}

void GlfwWindow::poll_events() {
  glfwPollEvents();
}

void GlfwWindow::wait_events(double timeout) {
  glfwWaitEventsTimeout(timeout);
}

void GlfwWindow::wake() {
  glfwPostEmptyEvent();
}

double GlfwWindow::take_scroll() {
  const double s = scroll_;
  scroll_ = 0.0;
  return s;
}

std::vector<std::string> GlfwWindow::take_dropped_paths() {
  return std::exchange(dropped_, {});
}

void GlfwWindow::begin_ui_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void GlfwWindow::end_ui_frame() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void GlfwWindow::swap() {
  glfwSwapBuffers(window_);
}

}  // namespace dynamesh
