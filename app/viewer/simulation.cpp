#include "app/viewer/simulation.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <exception>
#include <stdexcept>

#include "app/render/color_mode.h"
#include "core/adapt/workload_check.h"

namespace dynamesh {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

bool same_surface(const SimulationControls& a, const SimulationControls& b) {
  return a.scene == b.scene && a.scene_text == b.scene_text &&
         a.scene_parameters == b.scene_parameters;
}

// Everything but the scene and the seed: what Adapter::set_options can change.
bool same_adaptation(const SimulationControls& a, const SimulationControls& b) {
  return a.threshold == b.threshold && a.epsilon == b.epsilon && a.density == b.density &&
         a.k == b.k && a.smooth_iterations == b.smooth_iterations &&
         a.smooth_settled == b.smooth_settled && a.edge_length == b.edge_length &&
         a.max_triangles == b.max_triangles;
}

CriterionList criteria_for(const SimulationControls& c, const Surface& surface) {
  double scene_edge_length = 0.0;
  for (const SurfaceParameter& p : surface.parameters())
    if (p.name == "L") scene_edge_length = p.value;
  return default_criteria(c.scene, scene_edge_length, adapt_options(c), c.edge_length);
}

// Issue 15: a surface that no mesh can follow, or that needs more than the budgets, is
// refused before the adapter starts (the message is shown; the window never waits on it).
// Everything is checked at the request's time; the budgets over the whole of [0, 1] (the
// viewer may be sent anywhere). The surface is left at `time`.
void check_workload(const SimulationControls& c, Surface& surface, double time) {
  const AdaptOptions o = adapt_options(c);
  WorkloadBudget budget;
  budget.threshold = o.threshold;
  budget.density = o.density;
  budget.max_triangles = static_cast<double>(o.max_triangles);
  budget.max_samples = static_cast<double>(o.max_samples);
  budget.hopeless = c.scene == "expr" ? 1.0 : 10.0;
  set_edge_length_demand(budget, c.scene, surface, c.edge_length);
  const WorkloadWords words{"T",
                            "density",
                            "the triangle budget",
                            "the sample budget",
                            "the edge length",
                            "the scene's L"};
  std::string reason = workload_refusal(surface, budget, time, time, words);
  if (reason.empty())  // budgets only: a surface that breaks later shows its mesh until then
    reason = workload_refusal(surface, budget, 0.0, 1.0, words, 5, false);
  surface.set_time(time);
  if (!reason.empty()) throw std::invalid_argument("scene " + c.scene + " " + reason);
}

}  // namespace

AdaptOptions adapt_options(const SimulationControls& c) {
  AdaptOptions o;
  o.threshold = c.threshold;
  o.epsilon = c.epsilon;
  o.density = c.density;
  o.seed = c.seed;
  o.max_triangles = static_cast<std::size_t>(std::max(c.max_triangles, 0));
  o.smoothing.k = c.k;
  o.smoothing.iterations = c.smooth_iterations;
  o.smoothing.enabled = c.smooth_iterations > 0;
  o.smoothing.settled_offset = c.smooth_settled;
  return o;
}

Simulation::Simulation(ProgressCallback progress) : progress_(std::move(progress)) {}
Simulation::~Simulation() = default;

std::unique_ptr<Surface> Simulation::surface_for(const SimulationControls& c) {
  auto has_key = [&c](const auto& kv) {
    return std::any_of(c.scene_parameters.begin(), c.scene_parameters.end(),
                       [&kv](const auto& other) { return other.first == kv.first; });
  };
  // Parameters added or changed (none dropped, whose default only make_scene knows): set
  // them on the surface built already.
  if (surface_ && c.scene == built_.scene && c.scene_text == built_.scene_text &&
      std::all_of(built_.scene_parameters.begin(), built_.scene_parameters.end(), has_key)) {
    adapter_.reset();  // it refers to the surface about to change
    std::unique_ptr<Surface> surface = std::move(surface_);
    try {
      for (const auto& [name, value] : c.scene_parameters) {
        const std::vector<SurfaceParameter> now = surface->parameters();
        const auto it = std::find_if(now.begin(), now.end(),
                                     [&](const SurfaceParameter& p) { return p.name == name; });
        if (it == now.end() || it->value != value) surface->set_parameter(name, value);
      }
      return surface;
    } catch (const std::invalid_argument&) {
      // One at a time, a value may conflict with one set later: make_scene retries in any
      // order and says what is wrong when nothing works.
    }
  }
  return make_scene(c.scene, c.scene_parameters, c.scene_text, progress_);
}

void Simulation::rebuild(const StepRequest& request, StepTimings& timings) {
  const SimulationControls& c = request.controls;
  Clock::time_point start = Clock::now();
  double cpu = process_cpu_seconds();
  std::unique_ptr<Surface> surface = surface_for(c);
  adapter_.reset();
  surface_ = std::move(surface);
  built_ = c;  // also when the adapter fails below: surface_ matches c
  check_workload(c, *surface_, request.time);
  timings.build_seconds = seconds_since(start);
  timings.build_cpu_seconds = process_cpu_seconds() - cpu;
  start = Clock::now();
  cpu = process_cpu_seconds();
  adapter_ = std::make_unique<Adapter>(*surface_, adapt_options(c), criteria_for(c, *surface_));
  adapter_->initialize();
  timings.adapt_seconds = seconds_since(start);
  timings.adapt_cpu_seconds = process_cpu_seconds() - cpu;
}

SnapshotFields Simulation::snapshot_fields(const SnapshotFields& requested) const {
  SnapshotFields fields = requested;
  fields.error = true;
  fields.quantities.clear();
  // Point quantities that some colour mode shows (the mri scene's "intensity").
  for (const std::string& q : surface_->point_quantities()) {
    const bool shown = std::any_of(kAllColorModes.begin(), kAllColorModes.end(),
                                   [&q](ColorMode m) { return color_mode_field(m) == q; });
    if (shown) fields.quantities.push_back(q);
  }
  return fields;
}

StepResult Simulation::step(const StepRequest& request) {
  StepResult result;
  const SimulationControls& c = request.controls;
  if (!request.restart && failed_ && *failed_ == c) {
    result.error = failure_;  // not again: the same controls failed already
    return result;
  }
  try {
    const bool new_adapter =
        request.restart || !adapter_ || !same_surface(c, built_) || c.seed != built_.seed;
    StepTimings timings;
    if (new_adapter) {
      rebuild(request, timings);
      result.stepped = true;
    } else {
      const bool retune = !same_adaptation(c, built_);
      if (retune) {
        check_workload(c, *surface_, surface_->time());
        adapter_->set_options(adapt_options(c), criteria_for(c, *surface_));
        built_ = c;
      }
      if (retune || request.time != surface_->time()) {
        const Clock::time_point start = Clock::now();
        const double cpu = process_cpu_seconds();
        adapter_->step(request.time);
        timings.adapt_seconds = seconds_since(start);
        timings.adapt_cpu_seconds = process_cpu_seconds() - cpu;
        result.stepped = true;
      }
    }
    failed_.reset();
    const Clock::time_point start = Clock::now();
    result.snapshot =
        std::make_shared<const MeshSnapshot>(adapter_->snapshot(snapshot_fields(request.fields)));
    timings.snapshot_seconds = seconds_since(start);
    result.timings = timings;
    result.stats = adapter_->stats();
    result.scene = built_.scene;
    result.scene_text = built_.scene_text;
    result.parameters = surface_->parameters();
  } catch (const std::exception& e) {
    // The adapter may be half-way through a step: start again from the base mesh next time.
    adapter_.reset();
    failed_ = c;
    failure_ = e.what();
    result = StepResult{};
    result.error = failure_;
  }
  return result;
}

}  // namespace dynamesh
