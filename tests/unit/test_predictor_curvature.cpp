// ErrorPredictor::select's curvature estimate (the radius the travel guard holds vertices
// against) is the largest |n_b - n_a| / |b - a| over the mesh's edges, n the unit gradient of F
// at a corner. select skips the square root and the division for edges whose squared ratio
// cannot raise the maximum found so far (a division-free pre-test with a rounding margin);
// this checks that the result is still the exact maximum, recomputed here edge by edge from
// the surface, on adapted meshes large enough for the parallel loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/adapt/error_predictor.h"
#include "core/adapt/sample_store.h"
#include "core/adapt/surface_probe.h"
#include "core/parallel.h"
#include "core/surface/scene_registry.h"
#include "tests/support/error_only_adapter.h"

namespace dynamesh {
namespace {

// The unit normal select's frames hold for a corner of an implicit surface.
Vec3 unit_gradient(const ImplicitSurface& s, const Vec3& p) {
  Vec3 g;
  s.value_gradient(p, g);
  const double norm = g.norm();
  return norm > 0 ? Vec3(g / norm) : Vec3::Zero();
}

double brute_force_curvature(const Mesh48& mesh, const ImplicitSurface& s) {
  double largest = 0.0;
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    for (int e = 0; e < 3; ++e) {
      const Vec3 &a = mesh.position(v[(e + 1) % 3]), &b = mesh.position(v[(e + 2) % 3]);
      const double chord = (b - a).norm();
      if (chord > 0)
        largest = std::max(largest, (unit_gradient(s, b) - unit_gradient(s, a)).norm() / chord);
    }
  }
  return largest;
}

class PredictorCurvature : public ::testing::TestWithParam<const char*> {};

TEST_P(PredictorCurvature, RadiusIsTheExactLargestRatioOverTheEdges) {
  const std::unique_ptr<Surface> surface = make_scene(GetParam());
  surface->set_time(0.5);
  AdaptOptions o;
  o.threshold = 1e-3;
  o.epsilon = o.threshold / 4;
  const std::unique_ptr<Adapter> adapter = test::error_only_adapter(*surface, o);
  adapter->step(0.51);  // vertices moved off the initial lattice
  const Mesh48& mesh = adapter->mesh();
  ASSERT_GT(static_cast<std::int64_t>(mesh.face_capacity()), kParallelMin);
  // A fresh predictor: no references, so this one select sets the only finite radius.
  const SurfaceProbe probe(*surface);
  SampleStore samples(o.density, o.seed);
  ErrorPredictor predictor;
  predictor.begin_step(mesh, probe, mesh.positions(), 1);
  std::vector<Face> measure;
  predictor.select(mesh, probe, samples, {.asks = [](Face, double) { return false; }}, measure);
  EXPECT_EQ(measure.size(), mesh.n_faces());  // none has a reference yet
  const double largest = brute_force_curvature(mesh, static_cast<const ImplicitSurface&>(*surface));
  ASSERT_GT(largest, 0.0);
  EXPECT_EQ(predictor.curvature_radius(), 1.0 / largest);
}

INSTANTIATE_TEST_SUITE_P(Scenes, PredictorCurvature,
                         ::testing::Values("sphere", "capsule-bend", "twist"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace dynamesh
