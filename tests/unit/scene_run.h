// A scene and an Adapter on it, initialised at t0, for tests and benchmarks that drive the
// engine the way the CLI does.
#pragma once

#include <memory>
#include <string>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"

namespace dynamesh::test {

struct SceneRun {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
};

inline double scene_edge_length(const Surface& s) {
  for (const SurfaceParameter& p : s.parameters())
    if (p.name == "L") return p.value;
  return 0.0;
}

inline SceneRun start_scene(const std::string& scene, const AdaptOptions& options,
                            double t0 = 0.0) {
  SceneRun run;
  run.surface = make_scene(scene);
  run.surface->set_time(t0);
  run.adapter = std::make_unique<Adapter>(
      *run.surface, options,
      default_criteria(scene, scene_edge_length(*run.surface), options, 0.0));
  run.adapter->initialize();
  return run;
}

}  // namespace dynamesh::test
