#include "app/viewer/viewer_state.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "app/render/color_scale.h"
#include "core/io/atomic_file.h"
#include "core/io/number_text.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

// One text codec per field type.
std::string encode(double v) {
  return format_significant(v, 17);  // enough digits to read the same double back
}
std::string encode(float v) {
  return encode(static_cast<double>(v));
}
std::string encode(int v) {
  return std::to_string(v);
}
std::string encode(unsigned v) {
  return std::to_string(v);
}
std::string encode(bool v) {
  return v ? "true" : "false";
}
std::string encode(const std::string& v) {
  return v;
}
std::string encode(ColorMode v) {
  return std::string(color_mode_name(v));
}
std::string encode(ColorRange v) {
  ColorSettings c;
  c.range = v;
  return v == ColorRange::kFixed ? "fixed" : color_range_text(c);
}
std::string encode(const SceneSettings& v) {
  return encode(v.threshold) + " " + encode(v.epsilon) + " " + encode(v.density) + " " +
         encode(v.edge_length);
}
std::string encode(const glm::vec3& v) {
  return encode(v.x) + " " + encode(v.y) + " " + encode(v.z);
}
std::string encode(const glm::quat& q) {
  return encode(q.w) + " " + encode(q.x) + " " + encode(q.y) + " " + encode(q.z);
}

// Numbers as strictly as on the command line (core/io/number_text.h): the whole text, finite,
// in the type's range.
bool decode(const std::string& t, double& v) {
  const auto n = parse_finite_number(t);
  if (n) v = *n;
  return n.has_value();
}
bool decode(const std::string& t, float& v) {
  const auto n = parse_finite_number(t);
  if (!n || std::abs(*n) > 3e38) return false;
  v = static_cast<float>(*n);
  return true;
}
bool decode(const std::string& t, int& v) {
  const auto n = parse_whole_number(t, INT32_MIN, INT32_MAX);
  if (n) v = static_cast<int>(*n);
  return n.has_value();
}
bool decode(const std::string& t, unsigned& v) {
  const auto n = parse_whole_number(t, 0, UINT32_MAX);
  if (n) v = static_cast<unsigned>(*n);
  return n.has_value();
}
bool decode(const std::string& t, bool& v) {
  if (t != "true" && t != "false") return false;
  v = t == "true";
  return true;
}
bool decode(const std::string& t, std::string& v) {
  v = t;
  return true;
}
bool decode(const std::string& t, ColorMode& v) {
  const auto m = parse_color_mode(t);
  if (m) v = *m;
  return m.has_value();
}
bool decode(const std::string& t, ColorRange& v) {
  ColorSettings c;
  if (t == "fixed") {
    v = ColorRange::kFixed;
    return true;
  }
  try {
    parse_color_range(t, c);
  } catch (const std::invalid_argument&) {
    return false;
  }
  v = c.range;
  return true;
}
bool decode(const std::string& t, SceneSettings& v) {
  SceneSettings d;
  if (!(std::istringstream(t) >> d.threshold >> d.epsilon >> d.density >> d.edge_length))
    return false;
  // As validate_state's rules for the controls they become (inf passed `> 0`).
  const bool finite =
      std::isfinite(d.threshold) && std::isfinite(d.density) && std::isfinite(d.edge_length);
  if (!(finite && d.threshold > 0 && d.epsilon >= 0 && d.epsilon < d.threshold && d.density > 0 &&
        d.edge_length >= 0))
    return false;
  v = d;
  return true;
}
bool decode(const std::string& t, glm::vec3& v) {
  return static_cast<bool>(std::istringstream(t) >> v.x >> v.y >> v.z);
}
bool decode(const std::string& t, glm::quat& q) {
  return static_cast<bool>(std::istringstream(t) >> q.w >> q.x >> q.y >> q.z);
}

// Every saved field, once: save and load walk the same list, so they cannot disagree.
template <class State, class Visit>
void visit_fields(State& s, Visit&& visit) {
  visit("scene", s.controls.scene);
  visit("threshold", s.controls.threshold);
  visit("epsilon", s.controls.epsilon);
  visit("density", s.controls.density);
  visit("k", s.controls.k);
  visit("smooth_iterations", s.controls.smooth_iterations);
  visit("smooth_settled", s.controls.smooth_settled);
  visit("edge_length", s.controls.edge_length);
  visit("max_triangles", s.controls.max_triangles);
  visit("seed", s.controls.seed);
  visit("t0", s.t0);
  visit("t1", s.t1);
  visit("steps", s.steps);
  visit("time", s.time);
  visit("loop", s.loop);
  visit("camera.rotation", s.camera.rotation);
  visit("camera.target", s.camera.target);
  visit("camera.distance", s.camera.distance);
  visit("camera.fov_y_degrees", s.camera.fov_y_degrees);
  visit("camera.normalize_size", s.camera.normalize_size);
  visit("color_mode", s.style.mode);
  visit("error_viridis", s.style.colors.error_viridis);
  visit("intensity_auto", s.style.colors.intensity_auto);
  visit("intensity_window", s.style.colors.intensity_window);
  visit("intensity_level", s.style.colors.intensity_level);
  visit("intensity_viridis", s.style.colors.intensity_viridis);
  visit("color_range", s.style.colors.range);
  visit("color_range_min", s.style.colors.range_min);
  visit("color_range_max", s.style.colors.range_max);
  visit("wireframe", s.style.wireframe);
  visit("wire_width", s.style.wire_width);
  visit("show_panel", s.show_panel);
  visit("show_colorbar", s.show_colorbar);
  visit("window_x", s.window_x);
  visit("window_y", s.window_y);
  visit("window_width", s.window_width);
  visit("window_height", s.window_height);
  visit("output_dir", s.output_dir);
  visit("record_fps", s.record_fps);
}

}  // namespace

void save_viewer_state(const ViewerState& state, const std::string& path) {
  std::ostringstream out;
  out << "# dynamesh viewer state\n";
  visit_fields(state, [&out](const char* key, const auto& value) {
    out << key << " = " << encode(value) << "\n";
  });
  for (const auto& [name, value] : state.controls.scene_parameters) {
    out << "param." << name << " = " << encode(value) << "\n";
  }
  for (const auto& [name, value] : state.controls.scene_text) {
    out << "text." << name << " = " << value << "\n";
  }
  for (const auto& [scene, settings] : state.scene_settings) {
    out << "scene." << scene << " = " << encode(settings) << "\n";
  }
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) {
    std::error_code ignored;  // AtomicFile says what is wrong if the directory is missing
    fs::create_directories(parent, ignored);
  }
  AtomicFile file(path);
  file.stream() << out.str();
  file.commit();
}

bool load_viewer_state(ViewerState& state, const std::string& path,
                       std::vector<std::string>* rejected) {
  std::ifstream in(path);
  if (!in) return false;
  std::map<std::string, std::string> entries;
  ParameterOverrides parameters;
  TextOptions text;
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find(" = ");
    if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 3);
    double number = 0.0;
    if (key.rfind("param.", 0) == 0 && decode(value, number)) {
      parameters.emplace_back(key.substr(6), number);
    } else if (key.rfind("text.", 0) == 0) {
      text.emplace_back(key.substr(5), value);
    } else if (key.rfind("scene.", 0) == 0) {
      SceneSettings settings;
      if (decode(value, settings)) state.scene_settings[key.substr(6)] = settings;
    } else {
      entries[key] = value;
    }
  }
  visit_fields(state, [&entries, rejected](const char* key, auto& value) {
    const auto it = entries.find(key);
    if (it == entries.end()) return;
    auto decoded = value;
    if (decode(it->second, decoded))
      value = decoded;
    else if (rejected)
      rejected->push_back(key);
  });
  state.controls.scene_parameters = parameters;
  state.controls.scene_text = text;
  return true;
}

int ViewerState::keyframe_steps() const {
  return keyframes.size() < 2 ? 0 : static_cast<int>(keyframes.size() - 1) * std::max(steps, 1);
}

double ViewerState::keyframe_time(int step) const {
  if (keyframes.empty()) return t0;
  const int n = std::max(steps, 1);
  step = std::clamp(step, 0, keyframe_steps());
  const std::size_t segment = std::min<std::size_t>(step / n, keyframes.size() - 2);
  const double a = keyframes[segment], b = keyframes[segment + 1];
  return a + (b - a) * (step - static_cast<int>(segment) * n) / n;
}

std::pair<double, double> ViewerState::time_range() const {
  if (keyframes.empty()) return {t0, t1};
  const auto [lo, hi] = std::minmax_element(keyframes.begin(), keyframes.end());
  return {*lo, *hi};
}

void switch_scene(ViewerState& state, const std::string& scene) {
  SimulationControls& c = state.controls;
  if (scene == c.scene) return;
  state.scene_settings[c.scene] = {c.threshold, c.epsilon, c.density, c.edge_length};
  c.scene = scene;
  state.probe.reset();  // a point of the old scan
  c.scene_parameters.clear();
  c.scene_text.clear();
  SceneSettings next;
  if (const auto saved = state.scene_settings.find(scene); saved != state.scene_settings.end()) {
    next = saved->second;
  } else {
    for (const SceneInfo& info : list_scenes())
      if (info.name == scene) {
        next.threshold = info.suggested_threshold;
        next.density = info.suggested_density;
      }
    next.epsilon = 0.25 * next.threshold;
    next.edge_length = 0.0;
  }
  c.threshold = next.threshold;
  c.epsilon = next.epsilon;
  c.density = next.density;
  c.edge_length = next.edge_length;
  state.style.colors.threshold = c.threshold;
}

std::string settings_path() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  fs::path base;
  // The XDG base-directory specification ignores relative paths.
  if (xdg != nullptr && fs::path(xdg).is_absolute()) {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    base = fs::path(home) / ".config";
  } else {
    return {};
  }
  return (base / "dynamesh" / "viewer.conf").string();
}

}  // namespace dynamesh
