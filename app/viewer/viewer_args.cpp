#include "app/viewer/viewer_args.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "app/render/color_scale.h"
#include "app/viewer/simulation.h"
#include "core/adapt/adapt_options_check.h"
#include "core/io/number_text.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

// dynamesh-cli run's readers, with its messages (core/io/number_text.h).
double to_number(const std::string& option, const std::string& text) {
  return option_number(option, text);
}

int to_int(const std::string& option, const std::string& text, long long min = INT32_MIN,
           long long max = INT32_MAX) {
  return static_cast<int>(option_whole_number(option, text, min, max));
}

bool finite_in(double v, double lo, double hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

// Every value of the state, whether from the command line or from a saved settings file,
// with the command line's rules (dynamesh-cli run's where the option is shared).
void validate_state(const ViewerState& s) {
  const SimulationControls& c = s.controls;
  bool known = false;
  for (const SceneInfo& info : list_scenes()) known = known || info.name == c.scene;
  if (!known) {
    const std::string shown = c.scene.size() > 40 ? c.scene.substr(0, 40) + "..." : c.scene;
    throw std::invalid_argument("unknown scene '" + shown + "' (" + std::to_string(c.scene.size()) +
                                " characters; dynamesh-cli scenes lists them)");
  }
  // The adaptation's options as the simulation will use them, with the CLI's rules.
  const AdaptOptions adapt = adapt_options(c);
  if (const std::string problem = adapt_option_problem(adapt); !problem.empty())
    throw std::invalid_argument(problem);
  if (!(adapt.epsilon < adapt.threshold))
    throw std::invalid_argument("--epsilon must be in [0, threshold)");
  if (!(std::isfinite(c.edge_length) && c.edge_length >= 0))
    throw std::invalid_argument("--edge-length must be positive");
  if (s.steps < 1 || s.steps > kMaxSteps)
    throw std::invalid_argument("--steps must be between 1 and " + std::to_string(kMaxSteps));
  if (!(std::isfinite(s.t0) && std::isfinite(s.t1) && s.t0 >= 0 && s.t1 <= 1 && s.t0 <= s.t1))
    throw std::invalid_argument("--t0 and --t1 must satisfy 0 <= t0 <= t1 <= 1");
  if (!std::isfinite(s.time)) throw std::invalid_argument("time must be finite");
  if (s.window_width < 64 || s.window_height < 64 || s.window_width > 8192 ||
      s.window_height > 8192) {
    throw std::invalid_argument("--width and --height must be between 64 and 8192");
  }
  // Saved view settings (no command-line option): the ranges the panel offers.
  const Camera& cam = s.camera;
  if (!finite_in(cam.distance, 1e-4, 1e5))
    throw std::invalid_argument("camera.distance must be in [1e-4, 1e5]");
  if (!finite_in(cam.fov_y_degrees, 5, 120))
    throw std::invalid_argument("camera.fov_y_degrees must be in [5, 120]");
  const glm::quat& q = cam.rotation;
  const double q_norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!finite_in(q_norm, 0.5, 2.0))
    throw std::invalid_argument("camera.rotation must be a unit quaternion");
  for (int a = 0; a < 3; ++a)
    if (!finite_in(cam.target[a], -1e9, 1e9))
      throw std::invalid_argument("camera.target must be finite");
  if (!finite_in(s.style.wire_width, 0.5, 4.0))
    throw std::invalid_argument("wire_width must be in [0.5, 4] pixels");
  if (!finite_in(s.style.colors.intensity_window, 0, 1e9) ||
      !finite_in(s.style.colors.intensity_level, -1e9, 1e9))
    throw std::invalid_argument("intensity_window and intensity_level must be finite");
  if (s.record_fps < 1 || s.record_fps > 240)
    throw std::invalid_argument("record_fps must be between 1 and 240");
  if (std::abs(s.window_x) > 100000 || std::abs(s.window_y) > 100000)
    throw std::invalid_argument("window_x and window_y must be within 100000 pixels");
}

bool is_whole_number(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

// The scene text key an option sets (the same as dynamesh-cli run's), or null. --height is
// the window height when a whole number follows, as the CLI's image height is, and the
// height-field formula otherwise.
const char* text_option_key(const std::string& opt, const std::vector<std::string>& args,
                            std::size_t i) {
  static constexpr std::pair<const char*, const char*> kKeys[] = {
      {"--volume", "volume"},       {"--implicit", "implicit"},
      {"--height-field", "height"}, {"--parametric", "parametric"},
      {"--bounds", "bounds"},       {"--domain", "domain"},
      {"--periodic", "periodic"},   {"--base-mesh", "base-mesh"},
      {"--mask", "mask"},           {"--atlas", "atlas"}};
  for (const auto& [option, key] : kKeys)
    if (opt == option) return key;
  if (opt == "--height" && i + 1 < args.size() && !is_whole_number(args[i + 1])) return "height";
  return nullptr;
}

}  // namespace

std::string viewer_usage() {
  return "usage: dynamesh [--scene NAME] [--param KEY=VALUE] [--volume FILE] [--t0 T] [--t1 T]\n"
         "                [--mask FILE] [--atlas FILE] (mri: brain mask, label atlas)\n"
         "                [--keyframes T0,T1,...] (visited in order, --steps steps each)\n"
         "                [--steps N] [--threshold T] [--epsilon E] [--density D] [--k K]\n"
         "                [--smooth-iters I] [--smooth-settled F] [--edge-length L]\n"
         "                [--max-triangles M] [--seed S]\n"
         "                [--color shaded|error|curvature|valence|level|intensity|region]\n"
         "                [--play]\n"
         "                [--color-range frame|first|run|MIN,MAX] [--no-wireframe]\n"
         "                [--camera fit|AZ,EL[,DIST]] [--width W] [--height H]\n"
         "                [--state FILE | --fresh] [--version]\n"
         "each scene opens at the T, eps, density and edge length last used with it (the\n"
         "first time: the scene's suggestions, as dynamesh-cli run's defaults)\n"
         "a typed surface (scene expr; edit it in the panel's formula section):\n"
         "  --implicit F(x,y,z,t) --bounds xmin,ymin,zmin,xmax,ymax,zmax [--base-mesh FILE]\n"
         "  --height-field f(x,z,t) [--domain xmin,xmax,zmin,zmax]\n"
         "  --parametric \"X;Y;Z\" (in u,v,t) --domain umin,umax,vmin,vmax [--periodic u|v|uv]\n"
         "  (an example: xargs -d '\\n' -a assets/examples/pulsing-blob.args dynamesh)\n"
         "scripted runs (exit when done):\n"
         "  --frames N        N frames, one step each (waits for every step)\n"
         "  --run-for SEC     run SEC seconds as a session would (adapting with --play), print\n"
         "                    frame timing; --orbit: turn the view every frame meanwhile\n"
         "  --screenshot FILE.png  --record FILE.mp4  --frame-log FILE.csv\n"
         "settings (scene, parameters, view, window) are restored at start and saved at exit in\n"
         "  " +
         (settings_path().empty() ? std::string("$XDG_CONFIG_HOME/dynamesh/viewer.conf")
                                  : settings_path()) +
         "\n  (--state FILE: another file; --fresh: start from the defaults)\n"
         "keys: space play/pause, arrows step, W wireframe, C colour mode, F fit, P screenshot,\n"
         "      R record, H panel, Esc quit (settings saved).  mouse: left drag orbit, "
         "right/shift-left drag pan,\n"
         "      wheel zoom towards the cursor\n";
}

ViewerArgs parse_viewer_args(const std::vector<std::string>& args, const ViewerState& base) {
  ViewerArgs a;
  a.state = base;
  ViewerState& s = a.state;
  bool epsilon_given = false, threshold_given = false;
  // What the command line says about the scene, put over the saved settings at the end
  // (whatever the order of --scene and these options).
  ParameterOverrides parameters;
  TextOptions text;
  // Another scene opens at its own settings (or those last used with it), before the
  // options given here apply over them, whatever their order.
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--scene") {
      const std::string& name = args[i + 1];
      const std::vector<SceneInfo> scenes = list_scenes();
      if (std::none_of(scenes.begin(), scenes.end(),
                       [&](const SceneInfo& info) { return info.name == name; })) {
        std::string names;
        for (const SceneInfo& info : scenes) names += (names.empty() ? "" : ", ") + info.name;
        throw std::invalid_argument(
            "unknown scene '" +
            (name.size() > 40
                 ? name.substr(0, 40) + "...' (" + std::to_string(name.size()) + " characters)"
                 : name + "'") +
            " (scenes: " + names + ")");
      }
      switch_scene(s, name);
    }
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& opt = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(opt + " needs a value");
      if (args[i + 1].empty())
        throw std::invalid_argument(opt + " needs a value, got an empty string");
      return args[++i];
    };
    // A value's own parser does not know the option it came with: its message gets it.
    const auto naming_option = [&](auto&& parse) {
      try {
        return parse();
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(opt + ": " + e.what());
      }
    };
    if (opt == "--help" || opt == "-h") {
      a.help = true;
    } else if (opt == "--version") {
      a.version = true;
    } else if (opt == "--scene") {
      value();  // switched to above
    } else if (opt == "--param") {
      parameters.push_back(naming_option([&] { return parse_parameter_override(value()); }));
    } else if (const char* key = text_option_key(opt, args, i)) {
      text.emplace_back(key, value());
    } else if (opt == "--t0") {
      s.t0 = s.time = to_number(opt, value());
    } else if (opt == "--t1") {
      s.t1 = to_number(opt, value());
    } else if (opt == "--keyframes") {
      s.keyframes.clear();
      const std::string& list = value();
      for (std::size_t start = 0, comma; start <= list.size(); start = comma + 1) {
        comma = std::min(list.find(',', start), list.size());
        const double t = to_number(opt, list.substr(start, comma - start));
        if (!(t >= 0 && t <= 1)) throw std::invalid_argument("--keyframes: times lie in [0, 1]");
        s.keyframes.push_back(t);
      }
      if (s.keyframes.size() < 2)
        throw std::invalid_argument("--keyframes expects at least two times, e.g. 0,1,0");
    } else if (opt == "--steps") {
      s.steps = to_int(opt, value(), 1, kMaxSteps);
    } else if (opt == "--threshold") {
      s.controls.threshold = to_number(opt, value());
      threshold_given = true;
    } else if (opt == "--epsilon") {
      s.controls.epsilon = to_number(opt, value());
      epsilon_given = true;
    } else if (opt == "--density") {
      s.controls.density = to_number(opt, value());
    } else if (opt == "--wireframe" || opt == "--no-wireframe") {
      s.style.wireframe = opt == "--wireframe";
    } else if (opt == "--camera") {
      a.camera = naming_option([&] { return parse_camera_view(value()); });
    } else if (opt == "--color-range") {
      naming_option([&] { return parse_color_range(value(), s.style.colors); });
    } else if (opt == "--k") {
      s.controls.k = to_number(opt, value());
    } else if (opt == "--smooth-iters") {
      s.controls.smooth_iterations = to_int(opt, value(), 0, kMaxSmoothIterations);
    } else if (opt == "--smooth-settled") {
      s.controls.smooth_settled = to_number(opt, value());
    } else if (opt == "--edge-length") {
      s.controls.edge_length = to_number(opt, value());
    } else if (opt == "--max-triangles") {
      s.controls.max_triangles = to_int(opt, value(), kMinTriangleBudget, INT32_MAX);
    } else if (opt == "--seed") {
      s.controls.seed = static_cast<unsigned>(to_int(opt, value(), 0, INT32_MAX));
    } else if (opt == "--play") {
      s.playing = true;
    } else if (opt == "--frames") {
      a.frames = to_int(opt, value(), 1, kMaxSteps);
    } else if (opt == "--run-for") {
      a.run_for = to_number(opt, value());
      if (!(a.run_for > 0 && a.run_for <= 86400))
        throw std::invalid_argument("--run-for must be between 0 and 86400 seconds");
    } else if (opt == "--orbit") {
      a.orbit = true;
    } else if (opt == "--screenshot") {
      a.screenshot = value();
    } else if (opt == "--record") {
      a.record = value();
    } else if (opt == "--frame-log") {
      a.frame_log = value();
    } else if (opt == "--width") {
      s.window_width = to_int(opt, value(), 64, 8192);
    } else if (opt == "--height") {
      s.window_height = to_int(opt, value(), 64, 8192);
    } else if (opt == "--state") {
      a.state_file = value();
    } else if (opt == "--fresh") {
      a.fresh = true;
    } else if (opt == "--color") {
      const auto mode = parse_color_mode(value());
      if (!mode)
        throw std::invalid_argument(
            "--color expects shaded, error, curvature, valence, level, intensity or region");
      s.style.mode = *mode;
    } else {
      throw std::invalid_argument("unknown option '" + opt + "' (dynamesh --help lists them)");
    }
  }
  // Text options given here describe the surface whole: saved ones (another formula, another
  // volume) would only contradict them. (switch_scene dropped the other scene's.)
  s.controls.scene_parameters.insert(s.controls.scene_parameters.end(), parameters.begin(),
                                     parameters.end());
  if (!text.empty()) s.controls.scene_text = text;
  // As dynamesh-cli run: eps defaults to T/4.
  if (threshold_given && !epsilon_given) s.controls.epsilon = 0.25 * s.controls.threshold;
  validate_state(s);
  if (a.frames >= 0 && a.run_for >= 0)
    throw std::invalid_argument("--frames and --run-for exclude each other");
  if (!a.scripted() && (!a.screenshot.empty() || !a.record.empty() || !a.frame_log.empty()))
    throw std::invalid_argument(
        "--screenshot, --record and --frame-log need --frames or --run-for");
  if (a.frames == 0) throw std::invalid_argument("--frames must be at least 1");
  if (a.orbit && a.run_for < 0) throw std::invalid_argument("--orbit needs --run-for");
  if (!s.keyframes.empty()) {
    s.playhead = 0;
    s.time = s.keyframes.front();
  }
  const auto [first, last] = s.time_range();
  s.time = std::clamp(s.time, first, last);
  s.style.colors.threshold = s.controls.threshold;
  return a;
}

std::string state_file_for(const ViewerArgs& args) {
  if (!args.state_file.empty()) return args.state_file;
  return args.scripted() ? std::string() : settings_path();
}

}  // namespace dynamesh
