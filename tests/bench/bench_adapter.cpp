// Cost of one adaptation step against its yardstick (DESIGN.md, "Quality bars"): the pure
// cost of evaluating the surface once at every sample and every vertex, with the same
// threads. Goal (issue 4): step / yardstick <= 1.5, and a 100 000-triangle step well under
// 50 ms on the 2-core machine. Scenes twist and capsule-bend around t = 0.5, T = 1e-3.
// Predictive sampling (issue 17): BM_Sampling compares the median step with predictive and
// with full sampling on the same scene; goal: predictive <= 0.5x full. BM_SamplingInterleaved
// measures the same ratio with the two modes' steps alternating in one process.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "median.h"
#include "process_cpu_time.h"

namespace dynamesh {
namespace {

struct Scene {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
};

Scene adapted(const std::string& name, double threshold,
              Sampling sampling = Sampling::kPredictive) {
  Scene s;
  s.surface = make_scene(name);
  s.surface->set_time(0.5);
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  o.sampling = sampling;
  s.adapter = std::make_unique<Adapter>(*s.surface, o, default_criteria(name, 0.0, o, 0.0));
  s.adapter->initialize();
  return s;
}

// Every sample's and every vertex's position on the current mesh.
std::vector<Vec3> evaluation_points(const Adapter& a) {
  std::vector<Vec3> points;
  const Mesh48& mesh = a.mesh();
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    a.samples().for_each_sample(f, [&](const Vec3& b, double) {
      points.push_back(b[0] * mesh.position(v[0]) + b[1] * mesh.position(v[1]) +
                       b[2] * mesh.position(v[2]));
    });
  }
  for (Vertex v : mesh.live_vertices()) points.push_back(mesh.position(v));
  return points;
}

double yardstick_seconds(const ImplicitSurface& s, const std::vector<Vec3>& points) {
  const auto n = static_cast<std::int64_t>(points.size());
  double sink = 0;
  const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) reduction(+ : sink)
  for (std::int64_t i = 0; i < n; ++i) {
    Vec3 g;
    sink += s.value_gradient(points[static_cast<std::size_t>(i)], g) + g[0];
  }
  benchmark::DoNotOptimize(sink);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_Step(benchmark::State& state, const std::string& name, double threshold) {
  Scene s = adapted(name, threshold);
  double t = 0.5, total = 0, yard = 0;
  PhaseSeconds phases;
  std::int64_t steps = 0;
  for (auto _ : state) {
    t += 1e-3;  // a real, small deformation every step
    const StepStats& st = s.adapter->step(t);
    total += st.seconds.total;
    phases.project += st.seconds.project;
    phases.smooth += st.seconds.smooth;
    phases.sample += st.seconds.sample;
    phases.weld += st.seconds.weld;
    phases.split += st.seconds.split;
    state.PauseTiming();
    yard += yardstick_seconds(static_cast<const ImplicitSurface&>(*s.surface),
                              evaluation_points(*s.adapter));
    state.ResumeTiming();
    ++steps;
  }
  const auto per = [&](double x) { return 1e3 * x / static_cast<double>(steps); };
  state.counters["triangles"] = static_cast<double>(s.adapter->mesh().n_faces());
  state.counters["samples"] = static_cast<double>(s.adapter->samples().n_samples());
  state.counters["step_ms"] = per(total);
  state.counters["project_ms"] = per(phases.project);
  state.counters["smooth_ms"] = per(phases.smooth);
  state.counters["sample_ms"] = per(phases.sample);
  state.counters["weld_ms"] = per(phases.weld);
  state.counters["split_ms"] = per(phases.split);
  state.counters["yardstick_ms"] = per(yard);
  state.counters["ratio"] = total / yard;
}

// Median step (and each of its phases) with predictive or full sampling, t stepping by 1e-3
// from 0.5 after 8 warm-up steps (predictive sampling needs a step to have references); also
// the median step in process CPU time (median_step_cpu_ms), for a loaded machine.
void BM_Sampling(benchmark::State& state, const std::string& name, double threshold,
                 Sampling sampling) {
  Scene s = adapted(name, threshold, sampling);
  double t = 0.5;
  for (int i = 0; i < 8; ++i) s.adapter->step(t += 1e-3);
  std::vector<double> step, project, smooth, sample, weld, split, cpu;
  double measured = 0, faces = 0;
  for (auto _ : state) {
    const double cpu_before = process_cpu_seconds();
    const StepStats& st = s.adapter->step(t += 1e-3);
    cpu.push_back(process_cpu_seconds() - cpu_before);
    step.push_back(st.seconds.total);
    project.push_back(st.seconds.project);
    smooth.push_back(st.seconds.smooth);
    sample.push_back(st.seconds.sample);
    weld.push_back(st.seconds.weld);
    split.push_back(st.seconds.split);
    measured += static_cast<double>(st.faces_measured);
    faces += static_cast<double>(st.triangles);
  }
  state.counters["triangles"] = static_cast<double>(s.adapter->mesh().n_faces());
  state.counters["median_step_ms"] = 1e3 * median(step);
  state.counters["median_project_ms"] = 1e3 * median(project);
  state.counters["median_smooth_ms"] = 1e3 * median(smooth);
  state.counters["median_sample_ms"] = 1e3 * median(sample);
  state.counters["median_weld_ms"] = 1e3 * median(weld);
  state.counters["median_split_ms"] = 1e3 * median(split);
  state.counters["median_step_cpu_ms"] = 1e3 * median(cpu);
  state.counters["measured_share"] = measured / faces;
}

BENCHMARK_CAPTURE(BM_Sampling, twist_predictive, std::string("twist"), 1e-3, Sampling::kPredictive)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);
BENCHMARK_CAPTURE(BM_Sampling, twist_full, std::string("twist"), 1e-3, Sampling::kFull)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);
BENCHMARK_CAPTURE(BM_Sampling, capsule_predictive, std::string("capsule-bend"), 1e-3,
                  Sampling::kPredictive)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);
BENCHMARK_CAPTURE(BM_Sampling, capsule_full, std::string("capsule-bend"), 1e-3, Sampling::kFull)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);

// The goal's ratio measured with the two modes interleaved: one process keeps a predictive and
// a full-sampling adapter on the same scene and times their steps alternately, through the
// same times (the same decisions, so the same meshes). BM_Sampling times the two modes in
// separate runs, seconds apart, and this VM's speed drifts by up to 20% between them, as much
// as the goal's margin: its ratio came out 0.447, 0.573 and 0.527 for the same code. Here a
// drift slows both modes alike. Reported: the ratio of the medians, and the median over the
// pairs of each pair's ratio (a predictive step over the full step right after it), in wall
// and in process CPU time.
void BM_SamplingInterleaved(benchmark::State& state, const std::string& name, double threshold) {
  Scene predictive = adapted(name, threshold, Sampling::kPredictive);
  Scene full = adapted(name, threshold, Sampling::kFull);
  double t = 0.5;
  for (int i = 0; i < 8; ++i) {
    t += 1e-3;
    predictive.adapter->step(t);
    full.adapter->step(t);
  }
  std::vector<double> wall[2], cpu[2], wall_ratio, cpu_ratio;
  // Each phase's wall time per mode: run with one and with two threads, they show which phase
  // gains less from the second core (session 25: the weld pass's candidates on the twist, one
  // block of an order-keeping scan, took as long on two threads as on one).
  constexpr int kPhases = 5;
  const char* phase_names[kPhases] = {"project", "smooth", "sample", "weld", "split"};
  std::vector<double> phase[2][kPhases];
  for (auto _ : state) {
    t += 1e-3;
    for (int mode = 0; mode < 2; ++mode) {
      Adapter& a = *(mode == 0 ? predictive : full).adapter;
      const double cpu_before = process_cpu_seconds();
      const PhaseSeconds& p = a.step(t).seconds;
      wall[mode].push_back(p.total);
      cpu[mode].push_back(process_cpu_seconds() - cpu_before);
      const double seconds[kPhases] = {p.project, p.smooth, p.sample, p.weld, p.split};
      for (int k = 0; k < kPhases; ++k) phase[mode][k].push_back(seconds[k]);
    }
    wall_ratio.push_back(wall[0].back() / wall[1].back());
    cpu_ratio.push_back(cpu[0].back() / cpu[1].back());
  }
  state.counters["triangles"] = static_cast<double>(predictive.adapter->mesh().n_faces());
  state.counters["same_triangles"] =
      predictive.adapter->mesh().n_faces() == full.adapter->mesh().n_faces() ? 1.0 : 0.0;
  state.counters["predictive_ms"] = 1e3 * median(wall[0]);
  state.counters["full_ms"] = 1e3 * median(wall[1]);
  state.counters["ratio"] = median(wall[0]) / median(wall[1]);
  state.counters["pair_ratio"] = median(wall_ratio);
  state.counters["cpu_ratio"] = median(cpu[0]) / median(cpu[1]);
  state.counters["cpu_pair_ratio"] = median(cpu_ratio);
  for (int mode = 0; mode < 2; ++mode)
    for (int k = 0; k < kPhases; ++k)
      state.counters[std::string(mode == 0 ? "predictive_" : "full_") + phase_names[k] + "_ms"] =
          1e3 * median(phase[mode][k]);
}

BENCHMARK_CAPTURE(BM_SamplingInterleaved, twist, std::string("twist"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);
BENCHMARK_CAPTURE(BM_SamplingInterleaved, capsule, std::string("capsule-bend"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);

BENCHMARK_CAPTURE(BM_Step, twist_T1e - 3, std::string("twist"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_Step, capsule_T1e - 3, std::string("capsule-bend"), 1e-3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_Step, capsule_T2e - 4, std::string("capsule-bend"), 2e-4)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);
// About 100 000 triangles (the size goal).
BENCHMARK_CAPTURE(BM_Step, capsule_T9e - 5, std::string("capsule-bend"), 9e-5)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace
}  // namespace dynamesh
