// The closing JSON line of `dynamesh-cli run` (DESIGN.md, "Command line").
#pragma once

#include <string>
#include <vector>

#include "core/adapt/step_stats.h"
#include "core/geometry/mesh_quality.h"

namespace dynamesh {

struct RunSummary {
  std::string scene;
  int steps = 0;
  StepStats last;
  std::size_t total_splits = 0, total_welds = 0;
  double seconds_per_step_median = 0.0;
  double preparation_seconds = 0.0;  // building the scene (mri: reading and preprocessing)
  MeshQuality quality;
  bool budget_hit = false;  // in any step
  bool sample_budget_hit = false, time_budget_hit = false;
  std::uint64_t steps_done = 0;  // fewer than `steps` when the time budget stopped the run
  // Over the whole run, initialisation included: the most triangles and the largest sampled
  // error of any step, and the steps they occurred at (the last step alone may hide them).
  std::size_t peak_triangles = 0;
  std::uint64_t peak_triangles_step = 0;
  double worst_max_error = 0.0;
  std::uint64_t worst_max_error_step = 0;
  // The triangle count on arriving at each keyframe (the first: after initialisation).
  std::vector<std::size_t> keyframe_triangles;

  // Takes one step's statistics into the run's totals and extremes.
  void add(const StepStats& s);
  std::vector<TopologyEvent> topology_events;  // over the run (issue 16)
  std::size_t rebuilds = 0;                    // steps whose mesh was rebuilt from F
  std::size_t local_repairs = 0;               // events repaired locally (in steps not rebuilt)
  // The process's resident memory at the end of the run and its peak (Linux's VmRSS and
  // VmHWM, MiB; negative when unknown): a run's memory follows its mesh (issue 15's soak).
  double resident_mb = -1.0, peak_resident_mb = -1.0;
  void measure_resident_memory();
};

std::string to_json(const RunSummary& s);

}  // namespace dynamesh
