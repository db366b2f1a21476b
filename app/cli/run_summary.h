// The closing JSON line of `dynamesh-cli run` (DESIGN.md, "Command line").
#pragma once

#include <string>

#include "core/adapt/step_stats.h"
#include "core/geometry/mesh_quality.h"

namespace dynamesh {

struct RunSummary {
  std::string scene;
  int steps = 0;
  StepStats last;
  std::size_t total_splits = 0, total_welds = 0;
  double seconds_per_step_median = 0.0;
  MeshQuality quality;
  bool budget_hit = false;  // in any step
  std::vector<TopologyEvent> topology_events;  // over the run (issue 16)
  std::size_t rebuilds = 0;                    // steps whose mesh was rebuilt from F
};

std::string to_json(const RunSummary& s);

}  // namespace dynamesh
