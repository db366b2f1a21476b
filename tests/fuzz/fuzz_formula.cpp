// libFuzzer target: formula parsing and surface building of the `expr` scene, through the
// same make_scene call as dynamesh-cli. The first byte picks the kind (implicit, height
// field, parametric); the rest is the formula. A surface that builds and passes dynamesh-cli's
// feasibility check (workload_estimate.h, against the same small budgets) is adapted once.
// Bad formulas must end in std::invalid_argument or a refusal; a hang shows as a libFuzzer
// timeout.
#include <stdexcept>
#include <string>

#include "core/adapt/adapter.h"
#include "core/adapt/criteria.h"
#include "core/adapt/workload_estimate.h"
#include "core/surface/scene_registry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 400) return 0;
  static const char* kinds[] = {"implicit", "height", "parametric"};
  const std::string kind = kinds[data[0] % 3];
  const std::string formula(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    auto surface = dynamesh::make_scene("expr", {}, {{kind, formula}});
    dynamesh::AdaptOptions options;
    options.max_triangles = 2000;
    options.max_samples = 200000;
    const dynamesh::WorkloadEstimate w = dynamesh::estimate_workload(
        *surface, options.threshold, options.density, static_cast<double>(options.max_triangles));
    if (!w.problem.empty() || w.triangles > static_cast<double>(options.max_triangles) ||
        w.samples > static_cast<double>(options.max_samples))
      return 0;  // refused, as dynamesh-cli refuses it
    dynamesh::Adapter adapter(*surface, options,
                              dynamesh::default_criteria("expr", 0.0, options, 0.0));
    adapter.initialize();
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
