// The scene catalogue (SCENES.md): every scene by name, with a one-line description and its
// adjustable parameters, built with user overrides. The command line (--scene, --param) and
// the viewer's scene menu both go through here.
//
// The built-in scenes are listed in scene_registry.cpp; others (e.g. `mri`, `expr`) add
// themselves with register_scene() before the first lookup or from that list. A scene that
// needs text input (a file, an expression) reads it from SceneRequest::text_options.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

using ParameterOverrides = std::vector<std::pair<std::string, double>>;
using TextOptions = std::vector<std::pair<std::string, std::string>>;

struct SceneInfo {
  std::string name;
  std::string description;                   // one line
  std::vector<SurfaceParameter> parameters;  // defaults
};

// Builds a scene with its default parameters from its text options (empty for the built-in
// scenes); throws std::invalid_argument for bad options.
using SceneFactory = std::function<std::unique_ptr<Surface>(const TextOptions& options)>;

// Adds a scene to the catalogue. Throws std::invalid_argument if the name is taken.
// `parameters_known_without_options` = false for a scene whose factory cannot run without
// options (then list_scenes() shows no parameters for it).
void register_scene(const std::string& name, const std::string& description, SceneFactory factory,
                    bool parameters_known_without_options = true);

// Every registered scene, in registration order (built-ins first).
std::vector<SceneInfo> list_scenes();

// The named scene with `overrides` applied (at time 0). Throws std::invalid_argument with one
// line saying what is wrong and what is valid: unknown scene (lists the names), unknown
// parameter (lists the scene's), value out of range (gives the range) or an inconsistent
// combination. Overrides may come in any order: ones that conflict only with a default that
// a later override changes are retried.
std::unique_ptr<Surface> make_scene(const std::string& name,
                                    const ParameterOverrides& overrides = {},
                                    const TextOptions& text_options = {});

// "KEY=VALUE" (as given to --param) -> (KEY, VALUE); throws std::invalid_argument otherwise.
std::pair<std::string, double> parse_parameter_override(const std::string& text);

// Multi-line help text: each scene with its description, then its parameters with default,
// range and meaning.
std::string scene_help();

}  // namespace dynamesh
