#include "core/surface/scene_registry.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_set>

#include "core/surface/expression/expr_scene.h"
#include "core/surface/scenes/blobs_scene.h"
#include "core/surface/scenes/capsule_bend_scene.h"
#include "core/surface/scenes/sinc_scene.h"
#include "core/surface/scenes/sphere_scene.h"
#include "core/surface/scenes/twist_scene.h"
#include "core/surface/volume/mri_scene.h"

namespace dynamesh {

namespace {

void reject_text_options(const std::string& scene, const TextOptions& options) {
  if (options.empty()) return;
  throw std::invalid_argument(scene + ": takes no option '" + options.front().first +
                              "' (it only has numeric parameters, set with --param KEY=VALUE)");
}

template <class Scene>
SceneRegistration builtin() {
  SceneRegistration r;
  r.name = Scene::kName;
  r.description = Scene::kDescription;
  r.build = [](const SceneRequest& request) {
    reject_text_options(Scene::kName, request.text_options);
    return std::unique_ptr<Surface>(std::make_unique<Scene>());
  };
  return r;
}

// expr's parameters come from its formula: none are listed.
SceneRegistration expr_registration() {
  SceneRegistration r;
  r.name = ExprScene::kName;
  r.description = ExprScene::kDescription;
  r.build = [](const SceneRequest& request) { return make_expr_scene(request.text_options); };
  r.listed_parameters.emplace();
  return r;
}

// A static library drops object files nobody references, so the built-in scenes are listed
// here rather than registering themselves from their own files.
struct Catalogue {
  std::mutex mutex;
  std::vector<SceneRegistration> entries{builtin<SphereScene>(), builtin<CapsuleBendScene>(),
                                         builtin<SincScene>(),   builtin<TwistScene>(),
                                         expr_registration(),    mri_scene_registration(),
                                         builtin<BlobsScene>()};
};

Catalogue& catalogue() {
  static Catalogue c;
  return c;
}

std::string valid_names(const std::vector<SceneRegistration>& entries) {
  std::string list;
  for (const SceneRegistration& e : entries) list += (list.empty() ? "" : ", ") + e.name;
  return list;
}

// The last value given for each key wins, as on a command line; the keys keep the order of
// their last occurrence. Linear: a saved state with 200,000 `param.` lines took minutes with
// a pairwise comparison (issue 15).
ParameterOverrides last_value_per_key(const ParameterOverrides& overrides) {
  ParameterOverrides unique;
  std::unordered_set<std::string_view> seen;
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it)
    if (seen.insert(it->first).second) unique.push_back(*it);
  std::reverse(unique.begin(), unique.end());
  return unique;
}

// Applies every override (one value per key); one rejected only because of a value another override
// changes is retried after the others. Throws the first rejection that no order can fix.
void apply_overrides(Surface& scene, const ParameterOverrides& overrides) {
  ParameterOverrides pending = overrides;
  while (!pending.empty()) {
    ParameterOverrides failed;
    std::string first_error;
    for (const auto& [key, value] : pending) {
      try {
        scene.set_parameter(key, value);
      } catch (const std::invalid_argument& e) {
        if (failed.empty()) first_error = e.what();
        failed.emplace_back(key, value);
      }
    }
    if (failed.size() == pending.size()) throw std::invalid_argument(first_error);
    pending = std::move(failed);
  }
}

}  // namespace

void register_scene(SceneRegistration registration) {
  if (!registration.build) {
    throw std::invalid_argument("scene '" + registration.name + "' has no builder");
  }
  Catalogue& c = catalogue();
  const std::lock_guard lock(c.mutex);
  for (const SceneRegistration& e : c.entries) {
    if (e.name == registration.name) {
      throw std::invalid_argument("scene '" + registration.name + "' is already registered");
    }
  }
  c.entries.push_back(std::move(registration));
}

void register_scene(const std::string& name, const std::string& description, SceneFactory factory,
                    bool parameters_known_without_options) {
  SceneRegistration r;
  r.name = name;
  r.description = description;
  if (factory) {
    r.build = [factory = std::move(factory)](const SceneRequest& request) {
      return factory(request.text_options);
    };
  }
  if (!parameters_known_without_options) r.listed_parameters.emplace();
  register_scene(std::move(r));
}

std::vector<SceneInfo> list_scenes() {
  std::vector<SceneRegistration> entries;
  {
    Catalogue& c = catalogue();
    const std::lock_guard lock(c.mutex);
    entries = c.entries;
  }
  std::vector<SceneInfo> infos;
  for (const SceneRegistration& e : entries) {
    SceneInfo info;
    info.name = e.name;
    info.description = e.description;
    info.parameters = e.listed_parameters ? *e.listed_parameters : e.build({})->parameters();
    info.suggested_threshold = e.suggestions.threshold;
    info.suggested_density = e.suggestions.density;
    info.parameters_depend_on_input = e.listed_parameters.has_value();
    infos.push_back(std::move(info));
  }
  return infos;
}

std::unique_ptr<Surface> make_scene(const std::string& name, const ParameterOverrides& overrides,
                                    const TextOptions& text_options,
                                    const ProgressCallback& progress, double max_memory_mb) {
  SceneBuilder build;
  {
    Catalogue& c = catalogue();
    const std::lock_guard lock(c.mutex);
    for (const SceneRegistration& e : c.entries) {
      if (e.name == name) build = e.build;
    }
    if (!build) {
      throw std::invalid_argument("unknown scene '" + name +
                                  "'; valid scenes are: " + valid_names(c.entries));
    }
  }
  const ParameterOverrides unique = last_value_per_key(overrides);
  std::unique_ptr<Surface> scene = build({text_options, unique, progress, max_memory_mb});
  apply_overrides(*scene, unique);
  scene->set_time(0.0);
  return scene;
}

std::pair<std::string, double> parse_parameter_override(const std::string& text) {
  const std::size_t eq = text.find('=');
  const std::string key = text.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : text.substr(eq + 1);
  char* end = nullptr;
  const double number = value.empty() ? 0.0 : std::strtod(value.c_str(), &end);
  if (key.empty() || value.empty() || *end != '\0' || !std::isfinite(number)) {
    throw std::invalid_argument(
        "expected KEY=VALUE with a finite number VALUE (e.g. R0=0.8), got '" + text + "'");
  }
  return {key, number};
}

std::string scene_help() {
  std::ostringstream out;
  for (const SceneInfo& s : list_scenes()) {
    out << std::left << std::setw(14) << s.name << s.description << '\n';
    out << "    suggested: threshold " << s.suggested_threshold << ", density "
        << s.suggested_density
        << (s.parameters_depend_on_input ? "; ranges depend on the input" : "") << '\n';
    std::size_t name_width = 7;  // the columns line up within a scene
    for (const SurfaceParameter& p : s.parameters)
      name_width = std::max(name_width, p.name.size() + 2);
    for (const SurfaceParameter& p : s.parameters) {
      std::ostringstream range;
      range << '[' << p.min << ", " << p.max << ']';
      out << "    " << std::left << std::setw(static_cast<int>(name_width)) << p.name
          << std::setw(10) << p.value << std::setw(16) << range.str() << p.description << '\n';
    }
  }
  return out.str();
}

}  // namespace dynamesh
