#include "app/viewer/viewer_args.h"

#include <stdexcept>

#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

double to_number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) {
    throw std::invalid_argument(option + " expects a number, got '" + text + "'");
  }
  return v;
}

int to_int(const std::string& option, const std::string& text) {
  const double v = to_number(option, text);
  if (v != static_cast<int>(v)) throw std::invalid_argument(option + " expects an integer");
  return static_cast<int>(v);
}

}  // namespace

std::string viewer_usage() {
  return "usage: dynamesh [--scene NAME] [--param KEY=VALUE] [--t0 T] [--t1 T] [--steps N]\n"
         "                [--threshold T] [--epsilon E] [--density D] [--k K] [--smooth-iters I]\n"
         "                [--edge-length L] [--max-triangles M] [--seed S]\n"
         "                [--color shaded|error|curvature|valence|level|intensity] [--play]\n"
         "                [--width W] [--height H] [--state FILE]\n"
         "                [--frames N --screenshot FILE.png]   (scripted: run N steps, save, "
         "exit)\n"
         "keys: space play/pause, arrows step, W wireframe, C colour mode, F fit, P screenshot,\n"
         "      R record, H panel\n";
}

ViewerArgs parse_viewer_args(const std::vector<std::string>& args) {
  ViewerArgs a;
  ViewerState& s = a.state;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& opt = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(opt + " needs a value");
      return args[++i];
    };
    if (opt == "--help" || opt == "-h")
      a.help = true;
    else if (opt == "--scene")
      s.controls.scene = value();
    else if (opt == "--param")
      s.controls.scene_parameters.push_back(parse_parameter_override(value()));
    else if (opt == "--t0")
      s.t0 = s.time = to_number(opt, value());
    else if (opt == "--t1")
      s.t1 = to_number(opt, value());
    else if (opt == "--steps")
      s.steps = to_int(opt, value());
    else if (opt == "--threshold")
      s.controls.threshold = to_number(opt, value());
    else if (opt == "--epsilon")
      s.controls.epsilon = to_number(opt, value());
    else if (opt == "--density")
      s.controls.density = to_number(opt, value());
    else if (opt == "--k")
      s.controls.k = to_number(opt, value());
    else if (opt == "--smooth-iters")
      s.controls.smooth_iterations = to_int(opt, value());
    else if (opt == "--edge-length")
      s.controls.edge_length = to_number(opt, value());
    else if (opt == "--max-triangles")
      s.controls.max_triangles = to_int(opt, value());
    else if (opt == "--seed")
      s.controls.seed = static_cast<unsigned>(to_int(opt, value()));
    else if (opt == "--play")
      s.playing = true;
    else if (opt == "--frames")
      a.frames = to_int(opt, value());
    else if (opt == "--screenshot")
      a.screenshot = value();
    else if (opt == "--width")
      a.width = to_int(opt, value());
    else if (opt == "--height")
      a.height = to_int(opt, value());
    else if (opt == "--state")
      a.state_file = value();
    else if (opt == "--color") {
      const auto mode = parse_color_mode(value());
      if (!mode)
        throw std::invalid_argument(
            "--color expects shaded, error, curvature, valence, level or intensity");
      s.style.mode = *mode;
    } else {
      throw std::invalid_argument("unknown option '" + opt + "' (dynamesh --help lists them)");
    }
  }
  if (s.steps < 0) throw std::invalid_argument("--steps must be >= 0");
  if (a.width < 64 || a.height < 64 || a.width > 8192 || a.height > 8192) {
    throw std::invalid_argument("--width and --height must be between 64 and 8192");
  }
  if (!a.screenshot.empty() && a.frames < 0) a.frames = 0;
  if (a.frames >= 0 && a.screenshot.empty()) {
    throw std::invalid_argument("--frames needs --screenshot FILE.png");
  }
  s.style.colors.threshold = s.controls.threshold;
  return a;
}

}  // namespace dynamesh
