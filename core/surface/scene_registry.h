// The scene catalogue (SCENES.md): every scene by name, with a one-line description, its
// adjustable parameters and the adaptation settings that suit its units, built with user
// overrides. The command line (--scene, --param) and the viewer's scene menu both go through
// here.
//
// The built-in scenes (including `mri`) are listed in scene_registry.cpp; others (e.g.
// `expr`) add themselves with register_scene(). A scene that needs text input (a file, an
// expression) reads it from SceneRequest::text_options.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/surface/surface.h"
#include "core/surface/volume/progress.h"

namespace dynamesh {

using ParameterOverrides = std::vector<std::pair<std::string, double>>;
using TextOptions = std::vector<std::pair<std::string, std::string>>;

// Adaptation settings that suit a scene's units (AdaptOptions::threshold and ::density).
// The analytic scenes are about one unit across; `mri` is in millimetres. With another
// threshold T, density * suggested_threshold / T keeps the samples per triangle about the
// same: on a given surface a triangle with error T spans an area proportional to T
// (error ~ curvature * edge^2 / 8).
struct SceneSuggestions {
  double threshold = 0.008;  // scene units
  double density = 2000.0;   // samples per unit area (scene units squared)
};

struct SceneInfo {
  std::string name;
  std::string description;                   // one line
  std::vector<SurfaceParameter> parameters;  // defaults
  double suggested_threshold = SceneSuggestions{}.threshold;
  double suggested_density = SceneSuggestions{}.density;
  // True when `parameters` are nominal because their ranges depend on the scene's input
  // (mri: the volume's depth and intensities) and listing must not load it; the built
  // surface's parameters() has the exact ranges.
  bool parameters_depend_on_input = false;
};

// What make_scene hands a scene's builder.
struct SceneRequest {
  TextOptions text_options;
  // Last value per key. make_scene applies them after building; a builder may also build
  // with them directly when applying afterwards would redo expensive work (mri: a
  // segmentation threshold), as long as applying the same value again is free.
  ParameterOverrides overrides;
  // Stages of a long load (mri: "reading", "segmenting", "distance transform", "critical
  // points"), each with
  // the fraction done; may be empty. Only called during make_scene, from its thread.
  ProgressCallback progress;
  // Memory, MiB, the scene may plan to use while loading (mri: the volume's preprocessing);
  // a builder refuses, with an estimate, an input that would need more. 0: unchecked.
  double max_memory_mb = 0.0;
};

using SceneBuilder = std::function<std::unique_ptr<Surface>(const SceneRequest& request)>;

struct SceneRegistration {
  std::string name;
  std::string description;  // one line
  SceneBuilder build;
  // Shown by list_scenes() instead of building the scene with an empty request; set it for
  // a scene that cannot or should not be built just to be listed (then marked
  // parameters_depend_on_input).
  std::optional<std::vector<SurfaceParameter>> listed_parameters;
  SceneSuggestions suggestions;
};

// Adds a scene to the catalogue. Throws std::invalid_argument if the name is taken or the
// builder is empty.
void register_scene(SceneRegistration registration);

// Builds a scene with its default parameters from its text options (empty for the built-in
// scenes); throws std::invalid_argument for bad options.
using SceneFactory = std::function<std::unique_ptr<Surface>(const TextOptions& options)>;

// The same for a factory that only reads text options, with the default suggestions.
// `parameters_known_without_options` = false for a scene whose factory cannot run without
// options (then list_scenes() shows no parameters for it).
void register_scene(const std::string& name, const std::string& description, SceneFactory factory,
                    bool parameters_known_without_options = true);

// Every registered scene, in registration order (built-ins first). Loads no input files.
std::vector<SceneInfo> list_scenes();

// The named scene with `overrides` applied (at time 0). Throws std::invalid_argument with one
// line saying what is wrong and what is valid: unknown scene (lists the names), unknown
// parameter (lists the scene's), value out of range (gives the range), an inconsistent
// combination, or a bad text option (mri: a missing or unreadable volume). Overrides may
// come in any order: ones that conflict only with a default that a later override changes
// are retried. `progress` reports the stages of a long load (see SceneRequest).
std::unique_ptr<Surface> make_scene(const std::string& name,
                                    const ParameterOverrides& overrides = {},
                                    const TextOptions& text_options = {},
                                    const ProgressCallback& progress = {},
                                    double max_memory_mb = 0.0);

// "KEY=VALUE" (as given to --param) -> (KEY, VALUE); throws std::invalid_argument otherwise.
std::pair<std::string, double> parse_parameter_override(const std::string& text);

// Multi-line help text: each scene with its description and suggested threshold, then its
// parameters with default, range and meaning.
std::string scene_help();

}  // namespace dynamesh
