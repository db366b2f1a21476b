#include "app/viewer/viewer_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "app/render/mesh_renderer.h"
#include "app/render/png_file.h"
#include "app/viewer/glfw_window.h"
#include "app/viewer/simulation_driver.h"
#include "app/viewer/stats_history.h"
#include "app/viewer/video_recorder.h"
#include "app/viewer/viewer_panel.h"

namespace dynamesh {
namespace {

std::string timestamp() {
  char text[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(text, sizeof text, "%Y%m%d-%H%M%S", std::localtime(&now));
  return text;
}

// Mouse drag in progress, in normalised device coordinates of the 3D view.
struct Drag {
  int button = -1;
  glm::vec2 last{0.0f};
};

class ViewerApp {
 public:
  explicit ViewerApp(const ViewerArgs& args)
      : args_(args),
        state_(args.state),
        window_(args.width, args.height, "dynamesh"),
        driver_(make_simulation()) {
    if (!args.state_file.empty() && load_viewer_state(state_, args.state_file)) {
      status_ = "state restored from " + args.state_file;
    }
    glfwSetWindowUserPointer(window_.handle(), this);
    glfwSetScrollCallback(window_.handle(), [](GLFWwindow* w, double, double dy) {
      static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))->on_scroll(dy);
    });
    request(state_.time, true);
  }

  int run();

 private:
  // --- simulation ---------------------------------------------------------------------
  void request(double time, bool restart) {
    state_.time = time;
    driver_.request_step({time, state_.controls, restart});
  }
  void step_by(int direction) {
    const double dt = state_.time_step();
    double t = state_.time + direction * dt;
    bool restart = false;
    if (t > state_.t1 + 1e-12) {
      if (!state_.loop) {
        state_.playing = false;
        return;
      }
      t = state_.t0;
      restart = true;
    }
    request(std::max(state_.t0, t), restart);
  }
  void take_results();

  // --- frame ----------------------------------------------------------------------------
  glm::ivec4 view_rect() const;  // x, y, width, height of the 3D view in framebuffer pixels
  glm::vec2 cursor_ndc() const;
  void handle_mouse();
  void on_scroll(double dy);
  void handle_keys(PanelActions& a);
  void apply(const PanelActions& a);
  void render_frame(bool with_ui);
  Image read_window() const;
  void screenshot(const std::string& path);
  void toggle_recording();

  ViewerArgs args_;
  ViewerState state_;
  GlfwWindow window_;
  MeshRenderer renderer_;
  SimulationDriver driver_;
  std::shared_ptr<const MeshSnapshot> snapshot_;
  std::uint64_t results_seen_ = 0;
  ColorMode uploaded_mode_ = ColorMode::kShaded;
  bool camera_fitted_ = false;
  StatsHistory history_;
  StepStatistics last_stats_;
  std::string status_;
  VideoRecorder recorder_;
  Drag drag_;
  float fps_ = 0.0f;
};

void ViewerApp::take_results() {
  const std::uint64_t published = driver_.results_published();
  if (published != results_seen_) {
    results_seen_ = published;
    const StepResult r = driver_.latest_result();
    if (!r.error.empty()) status_ = "step failed: " + r.error;
    if (r.snapshot && r.snapshot != snapshot_) {
      snapshot_ = r.snapshot;
      renderer_.set_mesh(*snapshot_, state_.style.mode);
      uploaded_mode_ = state_.style.mode;
      if (r.error.empty()) {
        last_stats_ = r.stats;
        history_.add(snapshot_->time, r.stats);
      }
    }
  }
  if (snapshot_ && uploaded_mode_ != state_.style.mode) {
    renderer_.set_scalar(*snapshot_, state_.style.mode);  // colour mode changed: field only
    uploaded_mode_ = state_.style.mode;
  }
  if (snapshot_ && !camera_fitted_) {
    const glm::ivec4 v = view_rect();
    state_.camera.reset(renderer_.bounds(), float(v.z) / float(std::max(1, v.w)));
    camera_fitted_ = true;
  }
}

glm::ivec4 ViewerApp::view_rect() const {
  const glm::ivec2 fb = window_.framebuffer_size();
  const glm::ivec2 win = window_.window_size();
  const float scale = win.x > 0 ? float(fb.x) / float(win.x) : 1.0f;
  const int panel = state_.show_panel ? static_cast<int>(kPanelWidth * scale) : 0;
  return {panel, 0, std::max(1, fb.x - panel), std::max(1, fb.y)};
}

glm::vec2 ViewerApp::cursor_ndc() const {
  double x = 0, y = 0;
  glfwGetCursorPos(window_.handle(), &x, &y);
  const glm::ivec2 fb = window_.framebuffer_size(), win = window_.window_size();
  const float scale = win.x > 0 ? float(fb.x) / float(win.x) : 1.0f;
  const glm::ivec4 v = view_rect();
  return {2.0f * (float(x) * scale - float(v.x)) / float(v.z) - 1.0f,
          1.0f - 2.0f * float(y) * scale / float(v.w)};
}

void ViewerApp::handle_mouse() {
  GLFWwindow* w = window_.handle();
  const glm::vec2 p = cursor_ndc();
  const glm::ivec4 v = view_rect();
  const float aspect = float(v.z) / float(v.w);
  if (drag_.button < 0) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    for (int b : {GLFW_MOUSE_BUTTON_LEFT, GLFW_MOUSE_BUTTON_RIGHT, GLFW_MOUSE_BUTTON_MIDDLE}) {
      if (glfwGetMouseButton(w, b) == GLFW_PRESS) drag_ = {b, p};
    }
    return;
  }
  if (glfwGetMouseButton(w, drag_.button) != GLFW_PRESS) {
    drag_.button = -1;
    return;
  }
  const bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  if (drag_.button == GLFW_MOUSE_BUTTON_LEFT && !shift) {
    state_.camera.orbit(drag_.last, p);
  } else {
    state_.camera.pan(p - drag_.last, aspect);
  }
  drag_.last = p;
}

void ViewerApp::on_scroll(double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  const glm::ivec4 v = view_rect();
  state_.camera.zoom(std::pow(0.88f, float(dy)), cursor_ndc(), float(v.z) / float(v.w));
}

void ViewerApp::handle_keys(PanelActions& a) {
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  const auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
  if (pressed(GLFW_KEY_SPACE)) state_.playing = !state_.playing;
  if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) a.step_forward = true;
  if (ImGui::IsKeyPressed(GLFW_KEY_LEFT)) a.step_back = true;
  if (pressed(GLFW_KEY_W)) state_.style.wireframe = !state_.style.wireframe;
  if (pressed(GLFW_KEY_C)) {
    const auto i = std::find(kAllColorModes.begin(), kAllColorModes.end(), state_.style.mode);
    state_.style.mode =
        kAllColorModes[(std::size_t(i - kAllColorModes.begin()) + 1) % kAllColorModes.size()];
  }
  if (pressed(GLFW_KEY_F)) a.fit = true;
  if (pressed(GLFW_KEY_P)) a.screenshot = true;
  if (pressed(GLFW_KEY_R)) a.toggle_recording = true;
  if (pressed(GLFW_KEY_H)) state_.show_panel = !state_.show_panel;
}

void ViewerApp::apply(const PanelActions& a) {
  const glm::ivec4 v = view_rect();
  const float aspect = float(v.z) / float(v.w);
  if (a.restart)
    request(state_.t0, true);
  else if (a.step_forward)
    step_by(+1);
  else if (a.step_back)
    request(std::max(state_.t0, state_.time - state_.time_step()), false);
  else if (a.controls_changed)
    request(state_.time, false);
  if (a.fit) state_.camera.fit(renderer_.bounds(), aspect);
  if (a.reset_camera) state_.camera.reset(renderer_.bounds(), aspect);
  if (a.screenshot) {
    screenshot(
        (std::filesystem::path(state_.output_dir) / ("dynamesh-" + timestamp() + ".png")).string());
  }
  if (a.toggle_recording) toggle_recording();
  const std::string state_path =
      args_.state_file.empty() ? "dynamesh-viewer.state" : args_.state_file;
  if (a.save_state) {
    try {
      save_viewer_state(state_, state_path);
      status_ = "state saved to " + state_path;
    } catch (const std::exception& e) {
      status_ = e.what();
    }
  }
  if (a.load_state) {
    status_ = load_viewer_state(state_, state_path) ? "state loaded from " + state_path
                                                    : "cannot read " + state_path;
    request(state_.time, true);
  }
  if (a.reset_state) {
    state_ = ViewerState{};
    camera_fitted_ = false;
    request(state_.t0, true);
  }
}

void ViewerApp::render_frame(bool with_ui) {
  const glm::ivec2 fb = window_.framebuffer_size();
  renderer_.clear(state_.style, fb);
  const glm::ivec4 v = view_rect();
  renderer_.draw(state_.camera, state_.style, {v.z, v.w}, {v.x, v.y});
  if (with_ui) window_.end_ui_frame();
}

Image ViewerApp::read_window() const {
  const glm::ivec2 fb = window_.framebuffer_size();
  return read_framebuffer(fb.x, fb.y);
}

void ViewerApp::screenshot(const std::string& path) {
  try {
    write_png(read_window(), path);
    status_ = "screenshot " + path;
  } catch (const std::exception& e) {
    status_ = e.what();
  }
}

void ViewerApp::toggle_recording() {
  try {
    if (recorder_.recording()) {
      const std::string out = recorder_.stop();
      status_ = out.empty() ? "recording failed" : "recorded " + out;
    } else {
      const glm::ivec2 fb = window_.framebuffer_size();
      status_ = recorder_.start(state_.output_dir, "dynamesh-" + timestamp(), fb.x, fb.y,
                                state_.record_fps);
    }
  } catch (const std::exception& e) {
    status_ = e.what();
  }
}

int ViewerApp::run() {
  const bool scripted = args_.frames >= 0;
  int frames_done = 0;
  auto last = std::chrono::steady_clock::now();
  const auto started = last;
  while (!window_.should_close()) {
    const bool idle = !state_.playing && !driver_.busy() && !recorder_.recording() && !scripted;
    if (idle) {
      glfwWaitEventsTimeout(0.25);  // nothing moves: do not spin the CPU
    } else {
      glfwPollEvents();
    }
    if (scripted) {
      driver_.wait_idle();  // deterministic: each frame shows the step asked for before it
    }
    take_results();
    window_.begin_ui_frame();
    PanelInfo info{&history_,
                   last_stats_,
                   driver_.description(),
                   status_,
                   driver_.busy(),
                   recorder_.recording(),
                   fps_,
                   renderer_.shows_color_scale(state_.style),
                   renderer_.color_scale(state_.style)};
    PanelActions actions;
    if (state_.show_panel) actions = draw_panel(state_, info);
    if (info.has_scale && state_.show_colorbar) {
      const ImVec2 size = ImGui::GetIO().DisplaySize;
      draw_colorbar_window(info.scale, size.x, size.y);
    }
    handle_mouse();
    handle_keys(actions);
    if (scripted && frames_done < args_.frames) {
      actions.step_forward = frames_done > 0 || state_.time != state_.t0;
      ++frames_done;
    } else if (state_.playing && !driver_.busy()) {
      actions.step_forward = true;
    }
    apply(actions);
    render_frame(true);
    if (recorder_.recording()) recorder_.add_frame(read_window());
    if (scripted && frames_done >= args_.frames && !driver_.busy() &&
        driver_.results_published() == results_seen_) {
      write_png(read_window(), args_.screenshot);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      std::printf("dynamesh: %d frames in %.2f s (%zu triangles), screenshot %s\n", frames_done,
                  seconds, renderer_.n_triangles(), args_.screenshot.c_str());
      return 0;
    }
    window_.swap();
    const auto now = std::chrono::steady_clock::now();
    const float dt = std::chrono::duration<float>(now - last).count();
    last = now;
    if (dt > 0.0f) fps_ = fps_ == 0.0f ? 1.0f / dt : 0.9f * fps_ + 0.1f / dt;
  }
  recorder_.stop();
  return 0;
}

}  // namespace

int run_viewer(const ViewerArgs& args) {
  ViewerApp app(args);
  return app.run();
}

}  // namespace dynamesh
