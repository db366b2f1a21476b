// Scene parameters by name: a scene keeps its adjustable values in a plain struct and
// describes each field once (name, range, meaning); listing, range checking and assignment by
// name then come from that one table, so the command line and the viewer see the same thing.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

template <class Params>
struct ParameterSpec {
  const char* name;
  double Params::*field;
  double min;
  double max;
  const char* description;
};

// "sphere: no parameter 'R2'; valid parameters are R0, R1, L".
std::string unknown_parameter_message(const std::string& scene, const std::string& name,
                                      const std::vector<SurfaceParameter>& valid);
// Throws std::invalid_argument when value is not finite or outside [p.min, p.max].
void check_parameter_value(const std::string& scene, const SurfaceParameter& p, double value);

template <class Params, std::size_t N>
std::vector<SurfaceParameter> describe_parameters(const std::array<ParameterSpec<Params>, N>& specs,
                                                  const Params& values) {
  std::vector<SurfaceParameter> list;
  list.reserve(N);
  for (const auto& s : specs)
    list.push_back({s.name, values.*s.field, s.min, s.max, s.description});
  return list;
}

// Sets the named field after checking its range; throws std::invalid_argument otherwise.
template <class Params, std::size_t N>
void assign_parameter(const std::string& scene, const std::array<ParameterSpec<Params>, N>& specs,
                      Params& values, const std::string& name, double value) {
  const std::vector<SurfaceParameter> list = describe_parameters(specs, values);
  for (std::size_t i = 0; i < N; ++i) {
    if (name != specs[i].name) continue;
    check_parameter_value(scene, list[i], value);
    values.*specs[i].field = value;
    return;
  }
  throw std::invalid_argument(unknown_parameter_message(scene, name, list));
}

}  // namespace dynamesh
