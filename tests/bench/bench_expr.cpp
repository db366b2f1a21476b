// Typed formulas (issue 8) against the compiled scenes they equal: the same surface, evaluated
// through its formula's tape (formula_tape.h: values and exact derivatives on jets) or
// through C++ closed forms.
// Goal: a typed formula costs at most 5x its compiled equivalent for what sampling costs
// (implicit: value + gradient; parametric: position) and for the curvature the adapter
// needs per vertex (implicit: Hessian; parametric: derivatives), reported as the ratio of the
// pairs.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

constexpr int kPoints = 4096;

const char* kSphere = "sqrt(x^2+y^2+z^2) - 0.6*(9/0.6)^t";
const char* kSinc =
    "0.6*sin(2*pi*t)*(sqrt(x^2+z^2) < 1e-9 ? 1 : "
    "sin(4*pi*sqrt(x^2+z^2))/(4*pi*sqrt(x^2+z^2)))*exp(-0.5*sqrt(x^2+z^2))";

std::unique_ptr<Surface> scene(bool typed, bool sphere) {
  std::unique_ptr<Surface> s =
      !typed   ? make_scene(sphere ? "sphere" : "sinc")
      : sphere ? make_scene("expr", {}, {{"implicit", kSphere}, {"bounds", "-2,-2,-2,2,2,2"}})
               : make_scene("expr", {}, {{"height", kSinc}});
  s->set_time(0.3);
  return s;
}

// kPoints points uniformly in [-1, 1]^n, the same at every run.
template <class V>
std::vector<V> random_points() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<V> points(kPoints);
  for (V& p : points)
    for (int i = 0; i < p.size(); ++i) p[i] = u(rng);
  return points;
}

void sphere_value_gradient(benchmark::State& state) {
  const auto s = scene(state.range(0) != 0, true);
  const auto& f = dynamic_cast<const ImplicitSurface&>(*s);
  const std::vector<Vec3> points = random_points<Vec3>();
  for (auto _ : state) {
    double sum = 0;
    for (const Vec3& p : points) {
      Vec3 g;
      sum += f.value_gradient(p, g) + g.x();
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}

// Curvature needs the Hessian at every vertex.
void sphere_hessian(benchmark::State& state) {
  const auto s = scene(state.range(0) != 0, true);
  const auto& f = dynamic_cast<const ImplicitSurface&>(*s);
  const std::vector<Vec3> points = random_points<Vec3>();
  for (auto _ : state) {
    double sum = 0;
    for (const Vec3& p : points) sum += f.hessian(p)(0, 1);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}

template <bool kDerivatives>
void sinc_evaluation(benchmark::State& state) {
  const auto s = scene(state.range(0) != 0, false);
  const auto& f = dynamic_cast<const ParametricSurface&>(*s);
  const std::vector<Vec2> uvs = random_points<Vec2>();
  for (auto _ : state) {
    double sum = 0;
    for (const Vec2& uv : uvs) sum += kDerivatives ? f.derivatives(uv).su.y() : f.position(uv).y();
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}

// Argument: 0 = compiled scene, 1 = typed formula.
BENCHMARK(sphere_value_gradient)->Arg(0)->Arg(1);
BENCHMARK(sphere_hessian)->Arg(0)->Arg(1);
BENCHMARK(sinc_evaluation<false>)->Name("sinc_position")->Arg(0)->Arg(1);
BENCHMARK(sinc_evaluation<true>)->Name("sinc_derivatives")->Arg(0)->Arg(1);

}  // namespace
}  // namespace dynamesh
