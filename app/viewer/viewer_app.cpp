#include "app/viewer/viewer_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <thread>

#include "app/render/gl_api.h"
#include "app/render/mesh_renderer.h"
#include "app/render/png_file.h"
#include "app/render/render_target.h"
#include "app/render/surface_pick.h"
#include "app/viewer/frame_timing.h"
#include "app/viewer/glfw_window.h"
#include "app/viewer/simulation_driver.h"
#include "app/viewer/slice_panel.h"
#include "app/viewer/stats_history.h"
#include "app/viewer/video_recorder.h"
#include "app/viewer/viewer_panel.h"
#include "app/viewer/widget_report.h"
#include "core/io/atomic_file.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kMaxFps = 60;
constexpr auto kMinFrameInterval =
    std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / kMaxFps));

// Ctrl-C or a polite kill ends the session like closing the window: settings are saved. The
// signal's number, 0 until one comes.
volatile std::sig_atomic_t g_stop_signal = 0;

void on_stop_signal(int signal) {
  g_stop_signal = signal;
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string timestamp() {
  char text[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(text, sizeof text, "%Y%m%d-%H%M%S", std::localtime(&now));
  return text;
}

// The snapshot fields a colour mode needs besides the error (which is always there).
SnapshotFields fields_for(ColorMode mode) {
  SnapshotFields f;
  f.curvature = mode == ColorMode::kCurvature;
  f.valence = mode == ColorMode::kValence;
  f.level = mode == ColorMode::kLevel;
  return f;
}

// Everything the picture of the 3D view depends on: while it stays the same (the panel is
// used, the mouse moves), the last picture is copied in instead of drawing the mesh again,
// which costs a second per frame at a million triangles on a software renderer.
struct ViewKey {
  Camera camera;
  RenderStyle style;
  glm::ivec4 rect{0};
  int uploads = 0;  // mesh and colour uploads so far

  bool operator==(const ViewKey&) const = default;
};

// Mouse drag in progress, in normalised device coordinates of the 3D view.
struct Drag {
  int button = -1;
  glm::vec2 last{0.0f};
  glm::vec2 start{0.0f};  // where the button went down: a release there is a click
};

class ViewerApp {
 public:
  explicit ViewerApp(const ViewerArgs& args)
      : created_(Clock::now()),
        args_(args),
        state_(args.state),
        window_(state_.window_width, state_.window_height, "dynamesh"),
        driver_([] { GlfwWindow::wake(); }, [] { GlfwWindow::wake(); }),
        scenes_(list_scenes()),
        examples_(load_formula_examples(find_examples_dir())),
        // Multisampling doubles the cost of a frame on a software renderer: there, none.
        view_samples_(GlfwWindow::is_software_renderer(window_.renderer()) ? 1 : 4),
        // --camera: the first mesh is framed with that view, whatever was saved.
        fitted_scene_(args.camera ? std::string() : args.camera_scene),
        fitted_text_(args.camera_text) {
    startup_.window_seconds = ms_since(created_) * 1e-3;
    status_ = args.notice;  // e.g. why the saved settings were not used
    if (const char* path = std::getenv("DYNAMESH_WIDGET_REPORT")) widget_report_path_ = path;
    if (state_.window_x >= 0 && state_.window_y >= 0)
      window_.set_position({state_.window_x, state_.window_y});
    request(state_.time, true);
  }

  int run();

 private:
  // --- simulation ---------------------------------------------------------------------
  void request(double time, bool restart) {
    state_.time = time;
    driver_.request_step(
        {time, state_.controls, restart, fields_for(state_.style.mode), ++requests_made_});
  }
  void step_by(int direction);
  // Takes a new result if one was published; true when it shows a new step.
  bool take_results();

  // --- frame ----------------------------------------------------------------------------
  void wait_for_something_to_draw();
  glm::ivec4 view_rect() const;  // x, y, width, height of the 3D view in framebuffer pixels
  glm::vec2 cursor_ndc() const;
  void handle_mouse();
  // A click on the layer: the probed point moves to where the cursor's ray meets the mesh.
  void pick(const glm::vec2& ndc);
  // A scan dropped on the window (or typed): the mri scene on it, loaded on the worker.
  void open_scan(const std::string& path);
  // The answer to open_scan's request: a scan that cannot be read leaves the scene that was
  // on screen as it was (its controls back, its mesh adapted again), with the reason shown.
  void finish_opening(const StepResult& r);
  // What the scan says at the probed point; nullopt without a scan or a point.
  std::optional<VolumeProbe> current_probe() const;
  // The probed point marked in the 3D view, and the slices through it.
  void draw_probe(const VolumeProbe& probe, PanelActions& actions, bool report);
  void handle_keys(PanelActions& a);
  void apply(const PanelActions& a);
  void render_frame();
  Image read_window() const;
  void screenshot(const std::string& path);
  void toggle_recording();
  void start_recording(const std::string& dir, const std::string& stem);
  bool save_settings();  // false (and why in status_) when it fails
  void report_widgets(const std::vector<WidgetRect>& widgets, const VolumeProbe* probe);
  int finish_scripted(double seconds);
  // Whether anything could change the picture: input, a result, playing, a scripted run.
  bool needs_frame() const;
  // One frame: results, panel, actions, drawing. True when a scripted run is done (the
  // frame is then left in the back buffer, unswapped, for the screenshot).
  bool frame(bool timed_out);

  const Clock::time_point created_;
  ViewerArgs args_;
  ViewerState state_;
  GlfwWindow window_;
  MeshRenderer renderer_;
  SimulationDriver driver_;
  const std::vector<SceneInfo> scenes_;
  const std::vector<FormulaExample> examples_;  // the formula panel's library
  const int view_samples_;
  std::unique_ptr<RenderTarget> view_target_;
  std::optional<ViewKey> view_drawn_;  // what view_target_ holds
  std::shared_ptr<const MeshSnapshot> snapshot_;
  std::uint64_t snapshots_taken_ = 0;  // numbers snapshot_ (addresses may be reused)
  std::uint64_t results_seen_ = 0;
  // What the colour buffer holds: the field of this snapshot for this mode.
  std::uint64_t colored_snapshot_ = 0;
  ColorMode colored_mode_ = ColorMode::kShaded;
  std::uint64_t field_asked_for_ = 0;  // a missing field was asked for once for this one
  std::string fitted_scene_;           // the scene the camera was framed for
  TextOptions fitted_text_;            // and its text options
  std::string running_scene_;
  std::vector<SurfaceParameter> running_parameters_;
  TextOptions running_text_;
  StatsHistory history_;
  StepStats last_stats_;
  std::string error_, status_;
  VideoRecorder recorder_;
  Drag drag_;
  SlicePanel slices_;
  std::string progress_shown_;       // the loading progress the panel shows
  std::uint64_t requests_made_ = 0;  // StepRequest::id of the last request
  // A scan being opened: its path, the request that loads it, and the state to go back to.
  struct OpeningScan {
    std::string path;
    std::uint64_t request = 0;
    ViewerState before;
  };
  std::optional<OpeningScan> opening_;
  std::string open_error_;  // why the last scan opened could not be loaded
  std::uint64_t frames_drawn_ = 0;
  StartupTiming startup_;
  float fps_ = 0.0f;
  // Redraw only when something happened: input, a new result, or frames ImGui still needs.
  std::uint64_t input_events_seen_ = 0;
  int frames_to_draw_ = 2;
  std::vector<FrameSample> frames_;
  Clock::time_point started_, first_mesh_, last_frame_start_;
  std::optional<Clock::time_point> first_mesh_shown_;
  int scripted_frames_ = 0;
  // Test affordance (widget_report.h): the file named by DYNAMESH_WIDGET_REPORT, and what
  // was last written to it.
  std::string widget_report_path_, widget_report_written_;
};

void ViewerApp::step_by(int direction) {
  if (state_.keyframes.size() >= 2) {
    // Along the keyframes: there and back again (--keyframes 0,1,0) is steps, not a clamp.
    int next = state_.playhead + direction;
    bool restart = false;
    if (next > state_.keyframe_steps()) {
      if (!state_.loop) {
        state_.playing = false;
        return;
      }
      next = 0;
      restart = true;
    }
    state_.playhead = std::max(0, next);
    request(state_.keyframe_time(state_.playhead), restart);
    return;
  }
  double t = state_.time + direction * state_.time_step();
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

bool ViewerApp::take_results() {
  bool new_step = false;
  const std::uint64_t published = driver_.results_published();
  if (published != results_seen_) {
    results_seen_ = published;
    const StepResult r = driver_.latest_result();
    error_ = r.error;
    if (startup_.build_seconds == 0.0 && r.timings.build_seconds > 0.0) {
      startup_.build_seconds = r.timings.build_seconds;
      startup_.build_cpu_seconds = r.timings.build_cpu_seconds;
      startup_.adapt_seconds = r.timings.adapt_seconds;
      startup_.adapt_cpu_seconds = r.timings.adapt_cpu_seconds;
      startup_.snapshot_seconds = r.timings.snapshot_seconds;
    }
    if (!r.error.empty()) {
      state_.playing = false;  // the time would run on while the mesh stands still
    } else {
      running_scene_ = r.scene;
      running_parameters_ = r.parameters;
      running_text_ = r.scene_text;
    }
    // A new run (initialisation): fixed colour ranges (first frame, whole run) start again.
    if (r.error.empty() && r.stepped && r.stats.step == 0) renderer_.restart_color_range();
    if (r.snapshot && r.snapshot != snapshot_) {
      snapshot_ = r.snapshot;
      ++snapshots_taken_;
      const Clock::time_point start = Clock::now();
      renderer_.set_geometry(*snapshot_);  // once per step, never per frame
      if (startup_.upload_ms < 0.0) startup_.upload_ms = ms_since(start);
    }
    if (opening_ && r.request_id >= opening_->request) finish_opening(r);
    if (r.error.empty() && r.stepped) {
      last_stats_ = r.stats;
      history_.add(r.stats);
      for (const std::string& note : StatsHistory::topology_notes(r.stats))
        std::fprintf(stderr, "dynamesh: topology: %s\n", note.c_str());
      new_step = true;
    }
    frames_to_draw_ = std::max(frames_to_draw_, 1);
  }
  const ColorMode mode = state_.style.mode;
  if (snapshot_ && (colored_snapshot_ != snapshots_taken_ || colored_mode_ != mode)) {
    renderer_.set_scalar(*snapshot_, mode);
    colored_snapshot_ = snapshots_taken_;
    colored_mode_ = mode;
    // The mode changed to a field this snapshot was made without: a new snapshot (no step).
    const SnapshotFields wanted = fields_for(mode);
    const bool missing = (wanted.curvature || wanted.valence || wanted.level) &&
                         snapshot_->field(std::string(color_mode_field(mode))) == nullptr;
    if (missing && field_asked_for_ != snapshots_taken_ && error_.empty()) {
      field_asked_for_ = snapshots_taken_;
      request(state_.time, false);
    }
  }
  // A new scene is framed once (after its colours: the colour bar narrows the view); a new
  // formula (another example, a torus after a blob) too, seen from where the person looks.
  if (snapshot_ && (running_scene_ != fitted_scene_ || running_text_ != fitted_text_)) {
    const glm::ivec4 v = view_rect();
    const float aspect = float(v.z) / float(std::max(1, v.w));
    if (args_.camera && fitted_scene_.empty()) {
      state_.camera.look(*args_.camera, renderer_.bounds(), aspect);
    } else if (running_scene_ != fitted_scene_) {
      state_.camera.reset(renderer_.bounds(), aspect);
    } else {
      state_.camera.fit(renderer_.bounds(), aspect);
    }
    fitted_scene_ = running_scene_;
    fitted_text_ = running_text_;
  }
  return new_step;
}

void ViewerApp::wait_for_something_to_draw() {
  if (args_.frames >= 0) {
    window_.poll_events();  // scripted steps: the loop waits for the driver instead
  } else if (frames_to_draw_ > 0 || drag_.button >= 0 || args_.orbit) {
    // At most kMaxFps, as a display's refresh would pace swaps (a virtual display does not):
    // frames nobody can see would only take the cores from the adapter.
    std::this_thread::sleep_until(last_frame_start_ + kMinFrameInterval);
    window_.poll_events();
  } else {
    // Woken by input and by the driver when a result is published; the timeout is a
    // safety net only (and ends a timed run on time).
    window_.wait_events(args_.run_for >= 0 ? 0.1 : 1.0);
  }
  if (window_.input_events() != input_events_seen_) {
    input_events_seen_ = window_.input_events();
    frames_to_draw_ = std::max(frames_to_draw_, 3);  // ImGui settles within a few frames
  }
}

glm::ivec4 ViewerApp::view_rect() const {
  const glm::ivec2 fb = window_.framebuffer_size();
  const glm::ivec2 win = window_.window_size();
  const float scale = win.x > 0 ? float(fb.x) / float(win.x) : 1.0f;
  const int panel = state_.show_panel ? static_cast<int>(kPanelWidth * scale) : 0;
  const int bar = state_.show_colorbar && renderer_.shows_color_scale(state_.style)
                      ? static_cast<int>(kColorbarWidth * scale)
                      : 0;
  return {panel, 0, std::max(1, fb.x - panel - bar), std::max(1, fb.y)};
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
  const double scroll = window_.take_scroll();
  if (scroll != 0.0 && !ImGui::GetIO().WantCaptureMouse)
    state_.camera.zoom(std::pow(0.88f, float(scroll)), p, aspect);
  if (drag_.button < 0) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    for (int b : {GLFW_MOUSE_BUTTON_LEFT, GLFW_MOUSE_BUTTON_RIGHT, GLFW_MOUSE_BUTTON_MIDDLE}) {
      if (glfwGetMouseButton(w, b) == GLFW_PRESS) drag_ = {b, p, p};
    }
    return;
  }
  if (glfwGetMouseButton(w, drag_.button) != GLFW_PRESS) {
    // Released within 3 pixels of where it went down: a click, not an orbit.
    const glm::vec2 pixels = 0.5f * (p - drag_.start) * glm::vec2(v.z, v.w);
    if (drag_.button == GLFW_MOUSE_BUTTON_LEFT && glm::length(pixels) <= 3.0f) pick(drag_.start);
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

void ViewerApp::pick(const glm::vec2& ndc) {
  if (!snapshot_ || !snapshot_->volume) return;  // only a scan has something to say
  const glm::ivec4 v = view_rect();
  const auto hit = pick_surface(*snapshot_, state_.camera, renderer_.bounds(),
                                float(v.z) / float(std::max(1, v.w)), ndc);
  if (hit) state_.probe = *hit;
}

void ViewerApp::open_scan(const std::string& path) {
  // Opened while another is still loading: back to what was on screen before both.
  ViewerState before = opening_ ? opening_->before : state_;
  if (state_.controls.scene != "mri") switch_scene(state_, "mri");
  // The scan's own options only (a mask or an atlas belongs to the scan they came with).
  state_.controls.scene_text.clear();
  if (!path.empty()) state_.controls.scene_text = {{"volume", path}};
  state_.controls.scene_parameters.clear();
  state_.probe.reset();
  open_error_.clear();
  std::error_code ec;
  const bool folder = fs::is_directory(path, ec);
  status_ = "opening " + (path.empty() ? std::string("the default scan") : path) +
            (folder ? " (a DICOM series folder: converting it with dcm2niix)" : "");
  request(state_.time, true);
  opening_ = OpeningScan{path, requests_made_, std::move(before)};
}

void ViewerApp::finish_opening(const StepResult& r) {
  const OpeningScan opened = std::move(*opening_);
  opening_.reset();
  if (r.error.empty()) {
    status_ = "opened " + (opened.path.empty() ? std::string("the default scan") : opened.path);
    return;
  }
  open_error_ = "cannot open " + opened.path + ": " + r.error;
  status_.clear();
  const ViewerState& b = opened.before;
  state_.controls = b.controls;
  state_.scene_settings = b.scene_settings;
  state_.style.colors.threshold = b.style.colors.threshold;
  state_.probe = b.probe;
  error_.clear();
  // The failed request dropped the adapter; the scene's surface was kept (simulation.h), so
  // this adapts the mesh again without reading the old scan again.
  request(state_.time, true);
}

std::optional<VolumeProbe> ViewerApp::current_probe() const {
  const std::shared_ptr<const VolumeImage>& image = renderer_.volume();
  if (!image || !state_.probe || !snapshot_) return std::nullopt;
  // The layer's depth: depth_max * t (the mri scene's isolayer at time t).
  double depth = 0.0;
  for (const SurfaceParameter& p : running_parameters_)
    if (p.name == "depth_max") depth = p.value * snapshot_->time;
  return probe_volume(*image, *state_.probe, depth);
}

void ViewerApp::draw_probe(const VolumeProbe& probe, PanelActions& actions, bool report) {
  const glm::ivec4 v = view_rect();
  const glm::ivec2 fb = window_.framebuffer_size(), win = window_.window_size();
  const float to_window = fb.x > 0 ? float(win.x) / float(fb.x) : 1.0f;
  // The mark: the point projected as the renderer projects the mesh.
  const float aspect = float(v.z) / float(std::max(1, v.w));
  const SceneBounds& b = renderer_.bounds();
  const glm::vec4 clip = state_.camera.projection(aspect, b) * state_.camera.view() *
                         state_.camera.model(b) *
                         glm::vec4(float(probe.position.x()), float(probe.position.y()),
                                   float(probe.position.z()), 1.0f);
  if (clip.w > 0.0f) {
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const ImVec2 at((float(v.x) + 0.5f * (ndc.x + 1.0f) * float(v.z)) * to_window,
                    0.5f * (1.0f - ndc.y) * float(v.w) * to_window);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddCircle(at, 7.0f, IM_COL32(255, 60, 60, 255), 16, 2.0f);
    draw->AddCircleFilled(at, 2.5f, IM_COL32(255, 60, 60, 255));
  }
  const std::shared_ptr<const VolumeImage>& image = renderer_.volume();
  const ColorScale scale = renderer_.color_scale(state_.style);
  const Vec2 window =
      state_.style.mode == ColorMode::kIntensity ? Vec2(scale.min, scale.max) : image->window;
  const float x = (state_.show_panel ? kPanelWidth : 0.0f) + 8.0f;
  const float side = 170.0f;
  if (const auto moved =
          slices_.draw(*image, probe.position, snapshot_, window, x, float(win.y) - side - 48.0f,
                       side, report ? &actions.widgets : nullptr))
    state_.probe = *moved;
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
  // Esc quits as closing the window does: the settings are saved on the way out.
  if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
}

void ViewerApp::apply(const PanelActions& a) {
  const glm::ivec4 v = view_rect();
  const float aspect = float(v.z) / float(v.w);
  if (a.reset_settings) {
    // Everything back to its default but the window, which stays where the person put it.
    ViewerState defaults;
    defaults.window_x = state_.window_x;
    defaults.window_y = state_.window_y;
    defaults.window_width = state_.window_width;
    defaults.window_height = state_.window_height;
    state_ = defaults;
    fitted_scene_.clear();
    history_.clear();
    request(state_.t0, true);
    status_ = "settings reset to defaults";
  } else if (a.restart) {
    history_.clear();
    state_.playhead = 0;
    request(state_.keyframes.empty() ? state_.t0 : state_.keyframe_time(0), true);
  } else if (a.step_forward) {
    step_by(+1);
  } else if (a.step_back) {
    if (!state_.keyframes.empty())
      step_by(-1);
    else
      request(std::max(state_.t0, state_.time - state_.time_step()), false);
  } else if (a.controls_changed) {
    request(state_.time, false);
  }
  if (a.fit) state_.camera.fit(renderer_.bounds(), aspect);
  if (a.reset_camera) state_.camera.reset(renderer_.bounds(), aspect);
  if (a.toggle_recording) toggle_recording();
  if (a.open_requested) open_scan(a.open_path);
  if (a.save_settings) save_settings();
}

void ViewerApp::render_frame() {
  const glm::ivec4 v = view_rect();
  const UploadCounters& up = renderer_.uploads();
  const ViewKey key{state_.camera, state_.style, v, up.full + up.geometry + up.scalar};
  if (!view_target_ || view_target_->size() != glm::ivec2(v.z, v.w)) {
    view_target_ = std::make_unique<RenderTarget>(v.z, v.w, view_samples_);
    view_drawn_.reset();
  }
  if (view_drawn_ != key) {
    view_target_->bind();
    renderer_.clear(state_.style, {v.z, v.w});
    renderer_.draw(state_.camera, state_.style, {v.z, v.w});
    view_drawn_ = key;
  }
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  renderer_.clear(state_.style, window_.framebuffer_size());
  view_target_->present({v.x, v.y});
  window_.end_ui_frame();
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

void ViewerApp::start_recording(const std::string& dir, const std::string& stem) {
  const glm::ivec2 fb = window_.framebuffer_size();
  status_ = recorder_.start(dir, stem, fb.x, fb.y, state_.record_fps);
}

void ViewerApp::toggle_recording() {
  try {
    if (recorder_.recording()) {
      const int frames = recorder_.frames();
      const std::string out = recorder_.stop();
      status_ = out.empty() ? "recording failed"
                            : "recorded " + std::to_string(frames) + " frames: " + out;
    } else {
      start_recording(state_.output_dir, "dynamesh-" + timestamp());
    }
  } catch (const std::exception& e) {
    status_ = e.what();
  }
}

bool ViewerApp::save_settings() {
  if (args_.state_file.empty()) {
    status_ = "no settings file in a scripted run (give --state FILE)";
    return false;
  }
  const glm::ivec2 position = window_.position(), size = window_.window_size();
  state_.window_x = position.x;
  state_.window_y = position.y;
  state_.window_width = size.x;
  state_.window_height = size.y;
  try {
    save_viewer_state(state_, args_.state_file);
    status_ = "settings saved to " + args_.state_file;
    return true;
  } catch (const std::exception& e) {
    status_ = std::string("cannot save settings: ") + e.what();
    return false;
  }
}

void ViewerApp::report_widgets(const std::vector<WidgetRect>& widgets, const VolumeProbe* probe) {
  ShownState shown;
  shown.results = results_seen_;
  shown.busy = driver_.busy();
  shown.mesh = snapshot_.get();
  shown.samples = last_stats_.samples;
  shown.mean_error = last_stats_.mean_error;
  shown.probe = probe;
  shown.frames = frames_drawn_;
  shown.progress = progress_shown_;
  shown.scene = running_scene_;
  shown.scene_text = &running_text_;
  shown.error = error_;
  shown.open_error = open_error_;
  const std::string text = widget_report(widgets, state_.controls, shown);
  if (text == widget_report_written_) return;
  try {
    AtomicFile file(widget_report_path_);  // whole, so a reader never sees half of it
    file.stream() << text;
    file.commit();
    widget_report_written_ = text;
  } catch (const std::exception& e) {
    status_ = e.what();
  }
}

int ViewerApp::finish_scripted(double seconds) {
  // What the run was asked to show could not be shown (a scene or formula that does not
  // build): the screenshot shows the panel's red message over the last good mesh, the
  // recording is not kept, and the run fails with status 2, as dynamesh-cli does.
  if (!error_.empty()) recorder_.cancel();
  if (!args_.screenshot.empty()) write_png(read_window(), args_.screenshot);
  std::string recorded;
  if (recorder_.recording()) {
    const int frames = recorder_.frames();
    const std::string path = recorder_.stop();
    if (path.empty()) {
      std::fprintf(stderr, "dynamesh: recording to %s failed\n", args_.record.c_str());
      return 1;
    }
    recorded = ", recorded " + std::to_string(frames) + " frames to " + path;
  }
  if (!args_.frame_log.empty()) write_frame_log(frames_, args_.frame_log);
  const UploadCounters& up = renderer_.uploads();
  std::printf("dynamesh: %zu frames in %.2f s (%zu triangles)%s%s\n", frames_.size(), seconds,
              renderer_.n_triangles(),
              args_.screenshot.empty() ? "" : (", screenshot " + args_.screenshot).c_str(),
              recorded.c_str());
  std::printf(
      "dynamesh: scene %s, last step shown %llu (step 0 is the initialisation); uploads: "
      "%d full, %d positions only, %d colour\n",
      running_scene_.c_str(), static_cast<unsigned long long>(last_stats_.step), up.full,
      up.geometry, up.scalar);
  std::printf("dynamesh: %s\n", describe(summarize(frames_, seconds)).c_str());
  if (first_mesh_shown_) std::printf("dynamesh: %s\n", describe(startup_).c_str());
  if (!error_.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "dynamesh: error shown: %s\n", error_.c_str());
    return 2;
  }
  return 0;
}

bool ViewerApp::needs_frame() const {
  return args_.frames >= 0 || args_.orbit || frames_to_draw_ > 0 || drag_.button >= 0 ||
         driver_.results_published() != results_seen_ || (state_.playing && !driver_.busy()) ||
         driver_.progress() != progress_shown_;
}

bool ViewerApp::frame(bool timed_out) {
  if (args_.frames >= 0) {
    // Deterministic: frame 1 shows the initialisation (step 0), frame k shows step k - 1,
    // computed before the frame is drawn; N frames show steps 0 .. N - 1.
    if (scripted_frames_ > 0 && scripted_frames_ < args_.frames) step_by(+1);
    ++scripted_frames_;
    driver_.wait_idle();
  }
  const Clock::time_point frame_start = last_frame_start_ = Clock::now();
  FrameSample sample;
  sample.at_ms = std::chrono::duration<double, std::milli>(frame_start - started_).count();
  sample.new_step = take_results();
  sample.handoff_ms = ms_since(frame_start);

  const Clock::time_point draw_start = Clock::now();
  window_.begin_ui_frame();
  PanelInfo info;
  info.scenes = &scenes_;
  info.running_scene = running_scene_;
  info.running_parameters = running_parameters_;
  info.running_text = running_text_;
  info.examples = &examples_;
  info.history = &history_;
  info.last = last_stats_;
  info.error = error_;
  info.open_error = open_error_;
  info.status = status_;
  info.settings = args_.state_file;
  info.busy = driver_.busy();
  info.recorded_frames = recorder_.recording() ? recorder_.frames() : -1;
  info.fps = fps_;
  info.has_scale = renderer_.shows_color_scale(state_.style);
  info.scale = renderer_.color_scale(state_.style);
  info.report_widgets = !widget_report_path_.empty();
  for (const std::string& path : window_.take_dropped_paths()) open_scan(path);
  const std::optional<VolumeProbe> probe = current_probe();
  if (const auto& image = renderer_.volume()) {
    info.has_scan = true;
    info.scan_window = image->window;
  }
  info.probe = probe ? &*probe : nullptr;
  progress_shown_ = driver_.progress();
  info.progress = progress_shown_;
  PanelActions actions;
  if (state_.show_panel) actions = draw_panel(state_, info);
  if (info.has_scale && state_.show_colorbar) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    draw_colorbar_window(info.scale, size.x, size.y);
  }
  if (probe && snapshot_) draw_probe(*probe, actions, info.report_widgets);
  handle_mouse();
  handle_keys(actions);
  // Playing: the next step once the last one is on screen (so none is skipped, and a
  // recording gets one frame per step: a fixed time step per frame).
  const bool shown_latest = driver_.results_published() == results_seen_;
  if (args_.frames < 0 && state_.playing && !driver_.busy() && shown_latest) {
    actions.step_forward = true;
  }
  if (args_.orbit) state_.camera.orbit({0.0f, 0.0f}, {0.004f, 0.0f});  // as if dragged
  apply(actions);
  if (info.report_widgets) report_widgets(actions.widgets, probe ? &*probe : nullptr);
  render_frame();
  // Both read this frame, drawn but not yet swapped.
  if (actions.screenshot)
    screenshot((fs::path(state_.output_dir) / ("dynamesh-" + timestamp() + ".png")).string());
  if (recorder_.recording() && sample.new_step) recorder_.add_frame(read_window());
  const bool done = args_.frames >= 0 ? scripted_frames_ >= args_.frames && !driver_.busy() &&
                                            driver_.results_published() == results_seen_
                                      : timed_out;
  if (!done) window_.swap();  // the scripted screenshot reads the back buffer
  sample.draw_ms = ms_since(draw_start);
  sample.work_ms = ms_since(frame_start);
  sample.triangles = renderer_.n_triangles();
  ++frames_drawn_;
  if (!first_mesh_shown_ && renderer_.has_mesh()) {
    first_mesh_shown_ = Clock::now();
    startup_.first_mesh_seconds =
        std::chrono::duration<double>(*first_mesh_shown_ - created_).count();
    startup_.first_mesh_cpu_seconds = process_cpu_seconds();
    startup_.first_draw_ms = sample.draw_ms;
    startup_.volume_upload_ms = renderer_.volume_upload_ms();
  } else if (!first_mesh_shown_) {
    ++startup_.frames_before;
    startup_.frames_before_ms += sample.work_ms;
  }
  // Timing counts from the first frame with a mesh: before it, the panel alone is drawn.
  if (args_.scripted() && renderer_.has_mesh()) {
    if (frames_.empty()) first_mesh_ = frame_start;
    frames_.push_back(sample);
  }
  frames_to_draw_ = std::max(0, frames_to_draw_ - 1);
  // The rate frames could come at: waiting for events does not count.
  const float dt = static_cast<float>(sample.work_ms * 1e-3);
  if (dt > 0.0f) fps_ = fps_ == 0.0f ? 1.0f / dt : 0.9f * fps_ + 0.1f / dt;
  return done;
}

int ViewerApp::run() {
  started_ = Clock::now();
  if (!args_.record.empty()) {
    const fs::path target(args_.record);
    start_recording(target.parent_path().empty() ? "." : target.parent_path().string(),
                    target.stem().string());
  }
  int status = 0;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  while (!window_.should_close() && g_stop_signal == 0) {
    wait_for_something_to_draw();
    const bool timed_out = args_.run_for >= 0 && ms_since(started_) >= 1e3 * args_.run_for;
    if (!timed_out && !needs_frame()) continue;  // woken for nothing: the picture stands
    if (frame(timed_out)) {
      status = finish_scripted(frames_.empty() ? 0.0 : ms_since(first_mesh_) * 1e-3);
      break;
    }
  }
  if (recorder_.recording()) toggle_recording();
  if (g_stop_signal != 0 && args_.scripted()) {
    // Not done: say so, and what stays (the movie so far is a whole file, the screenshot and
    // frame log were not written), and end as the CLI does (128 + signal; issue 15).
    std::fprintf(stderr, "dynamesh: stopped by signal %d before the scripted run was done%s%s\n",
                 static_cast<int>(g_stop_signal), args_.record.empty() ? "" : "; ",
                 args_.record.empty() ? "" : status_.c_str());
    status = 128 + g_stop_signal;
  }
  if (!args_.state_file.empty() && !save_settings())
    std::fprintf(stderr, "dynamesh: %s\n", status_.c_str());
  return status;
}

}  // namespace

int run_viewer(const ViewerArgs& args) {
  ViewerApp app(args);
  return app.run();
}

}  // namespace dynamesh
