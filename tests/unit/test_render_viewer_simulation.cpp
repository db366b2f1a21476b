// The viewer's Simulation (the real Adapter behind the window) and its worker-thread driver,
// checked against the Adapter driven directly as dynamesh-cli run drives it.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <string>

#include "app/viewer/simulation.h"
#include "app/viewer/simulation_driver.h"
#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "core/surface/scenes/sphere_scene.h"
#include "test_render_step_request.h"

namespace dynamesh {
namespace {

SimulationControls coarse(const std::string& scene = "capsule-bend") {
  SimulationControls c;
  c.scene = scene;
  c.threshold = 0.02;
  c.epsilon = 0.005;
  c.density = 500;
  return c;
}

using test::at;

// The same adaptation without the viewer: the CLI's sequence of calls.
struct DirectRun {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;

  DirectRun(const SimulationControls& c, double t0) : surface(make_scene(c.scene)) {
    surface->set_time(t0);
    adapter = std::make_unique<Adapter>(*surface, adapt_options(c),
                                        default_criteria(c.scene, 0.0, adapt_options(c), 0.0));
    adapter->initialize();
  }
};

TEST(ViewerSimulation, InitialisesAndStepsLikeTheAdapterDrivenDirectly) {
  const SimulationControls c = coarse();
  Simulation sim;
  const StepResult first = sim.step(at(0.0, c, true));
  ASSERT_TRUE(first.error.empty()) << first.error;
  ASSERT_TRUE(first.snapshot);
  EXPECT_TRUE(first.stepped);
  EXPECT_EQ(first.stats.step, 0u);
  EXPECT_EQ(first.scene, "capsule-bend");
  EXPECT_EQ(first.snapshot->n_triangles(), first.stats.triangles);
  ASSERT_NE(first.snapshot->field("error"), nullptr);
  EXPECT_EQ(first.snapshot->field("curvature"), nullptr);  // not asked for

  DirectRun direct(c, 0.0);
  EXPECT_EQ(first.stats.triangles, direct.adapter->stats().triangles);
  EXPECT_EQ(first.stats.splits, direct.adapter->stats().splits);

  for (double t : {0.1, 0.2, 0.3}) {
    const StepResult r = sim.step(at(t, c));
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.stepped);
    const StepStats& d = direct.adapter->step(t);
    EXPECT_EQ(r.stats.step, d.step);
    EXPECT_EQ(r.stats.triangles, d.triangles);
    EXPECT_EQ(r.stats.splits, d.splits);
    EXPECT_EQ(r.stats.welds, d.welds);
    EXPECT_EQ(r.stats.vertices_kept, d.vertices_kept);
    EXPECT_DOUBLE_EQ(r.stats.max_error, d.max_error);
    EXPECT_GT(r.stats.vertices_kept, 0u);
    EXPECT_GT(r.stats.seconds.total, 0.0);
    EXPECT_DOUBLE_EQ(r.snapshot->time, t);
  }
}

TEST(ViewerSimulation, OtherFieldsAtTheSameTimeGiveASnapshotWithoutAStep) {
  const SimulationControls c = coarse();
  Simulation sim;
  sim.step(at(0.0, c, true));
  const StepResult moved = sim.step(at(0.2, c));
  StepRequest again = at(0.2, c);
  again.fields.curvature = true;
  again.fields.valence = true;
  const StepResult r = sim.step(again);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.stepped);
  EXPECT_EQ(r.stats.step, moved.stats.step);
  EXPECT_EQ(r.snapshot->positions, moved.snapshot->positions);
  const ScalarField* k = r.snapshot->field("curvature");
  const ScalarField* valence = r.snapshot->field("valence");
  ASSERT_NE(k, nullptr);
  ASSERT_NE(valence, nullptr);
  EXPECT_EQ(r.snapshot->field("level"), nullptr);
  // The capsule's radius is 0.4: curvature 2.5 across the tube, more inside the bend.
  float smallest = 1e9f;
  for (float x : k->values) smallest = std::min(smallest, x);
  EXPECT_NEAR(smallest, 2.5f, 0.3f);
  for (float v : valence->values) {
    EXPECT_GE(v, 3.0f);
    EXPECT_LE(v, 8.0f);
  }
}

TEST(ViewerSimulation, NewThresholdAdaptsTheMeshFromWhereItIs) {
  SimulationControls c = coarse();
  Simulation sim;
  sim.step(at(0.0, c, true));
  const StepResult before = sim.step(at(0.3, c));
  c.threshold = 0.005;
  c.epsilon = 0.00125;
  const StepResult r = sim.step(at(0.3, c));  // same time: options only
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.stepped);
  EXPECT_EQ(r.stats.step, before.stats.step + 1);  // a step, not a restart
  EXPECT_GT(r.stats.triangles, before.stats.triangles);
  // Mostly refinement: the vertices there were stay.
  EXPECT_GT(r.stats.vertices_kept, 9 * before.stats.vertices / 10);
  EXPECT_LE(r.stats.max_error, c.threshold + c.epsilon + 1e-12);

  // The same as set_options + step on the adapter driven directly.
  DirectRun direct(coarse(), 0.0);
  direct.adapter->step(0.3);
  direct.adapter->set_options(adapt_options(c),
                              default_criteria(c.scene, 0.0, adapt_options(c), 0.0));
  const StepStats& d = direct.adapter->step(0.3);
  EXPECT_EQ(r.stats.triangles, d.triangles);
  EXPECT_DOUBLE_EQ(r.stats.max_error, d.max_error);
}

TEST(ViewerSimulation, SceneParameterOrSeedRestartsWithTheNewValue) {
  SimulationControls c = coarse();
  Simulation sim;
  sim.step(at(0.0, c, true));
  sim.step(at(0.2, c));
  c.scene_parameters = {{"r", 0.3}};
  const StepResult r = sim.step(at(0.2, c));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.stats.step, 0u);  // re-initialised at the current time
  EXPECT_DOUBLE_EQ(r.snapshot->time, 0.2);
  bool found = false;
  for (const SurfaceParameter& p : r.parameters) {
    if (p.name == "r") {
      found = true;
      EXPECT_DOUBLE_EQ(p.value, 0.3);
    }
  }
  EXPECT_TRUE(found);
  // The radius reached the surface: the tube's curvature is now 1 / 0.3.
  StepRequest k = at(0.2, c);
  k.fields.curvature = true;
  const StepResult curved = sim.step(k);
  float smallest = 1e9f;
  for (float x : curved.snapshot->field("curvature")->values) smallest = std::min(smallest, x);
  EXPECT_NEAR(smallest, 1.0f / 0.3f, 0.4f);

  // Dropping the override goes back to the scene's default (built anew).
  c.scene_parameters.clear();
  const StepResult back = sim.step(at(0.2, c));
  for (const SurfaceParameter& p : back.parameters) {
    if (p.name == "r") {
      EXPECT_DOUBLE_EQ(p.value, 0.4);
    }
  }

  c.seed = 7;
  sim.step(at(0.3, c));
  const StepResult reseeded = sim.step(at(0.3, c));
  EXPECT_FALSE(reseeded.stepped);  // nothing changed since the restart above
  EXPECT_EQ(reseeded.stats.step, 0u);
}

TEST(ViewerSimulation, BadParameterAndUnknownSceneAreErrorsNotCrashes) {
  SimulationControls c = coarse();
  Simulation sim;
  ASSERT_TRUE(sim.step(at(0.0, c, true)).error.empty());
  c.scene_parameters = {{"no_such", 1.0}};
  const StepResult bad = sim.step(at(0.1, c));
  EXPECT_FALSE(bad.snapshot);
  EXPECT_NE(bad.error.find("no_such"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("valid parameters"), std::string::npos) << bad.error;
  // Asked again (the next frame of a playing viewer): the same error, at once.
  EXPECT_EQ(sim.step(at(0.2, c)).error, bad.error);

  c.scene_parameters = {{"r", 1e6}};  // out of range
  const StepResult range = sim.step(at(0.1, c));
  EXPECT_NE(range.error.find("r"), std::string::npos);

  c.scene_parameters.clear();
  c.scene = "no-such-scene";
  const StepResult unknown = sim.step(at(0.1, c));
  EXPECT_NE(unknown.error.find("capsule-bend"), std::string::npos) << unknown.error;

  c.scene = "sinc";  // a good scene works again
  const StepResult good = sim.step(at(0.1, c));
  ASSERT_TRUE(good.error.empty()) << good.error;
  EXPECT_EQ(good.scene, "sinc");
  EXPECT_GT(good.snapshot->n_triangles(), 0u);
}

// The sphere scene carrying a point quantity, as the mri scene carries its MR intensity.
class GlowingSphere final : public ImplicitSurface {
 public:
  std::string name() const override { return "test-glowing-sphere"; }
  void set_time(double t) override {
    ImplicitSurface::set_time(t);
    sphere_.set_time(t);
  }
  Box3 bounds() const override { return sphere_.bounds(); }
  Mesh48 base_mesh() const override { return sphere_.base_mesh(); }
  double value(const Vec3& p) const override { return sphere_.value(p); }
  double value_gradient(const Vec3& p, Vec3& g) const override {
    return sphere_.value_gradient(p, g);
  }
  Mat3 hessian(const Vec3& p) const override { return sphere_.hessian(p); }
  std::vector<std::string> point_quantities() const override { return {"intensity", "other"}; }
  double point_quantity(const std::string& name, const Vec3& p) const override {
    return name == "intensity" ? 100.0 + 10.0 * p.z() : 0.0;
  }

 private:
  SphereScene sphere_;
};

TEST(ViewerSimulation, SnapshotCarriesTheSurfaceIntensity) {
  static const bool registered = [] {
    register_scene("test-glowing-sphere", "a sphere with an intensity",
                   [](const TextOptions&) { return std::make_unique<GlowingSphere>(); });
    return true;
  }();
  ASSERT_TRUE(registered);
  SimulationControls c = coarse("test-glowing-sphere");
  Simulation sim;
  const StepResult r = sim.step(at(0.1, c, true));
  ASSERT_TRUE(r.error.empty()) << r.error;
  const ScalarField* intensity = r.snapshot->field("intensity");
  ASSERT_NE(intensity, nullptr);
  EXPECT_EQ(r.snapshot->field("other"), nullptr);  // no colour mode shows it
  ASSERT_EQ(intensity->values.size(), r.snapshot->n_vertices());
  for (std::size_t v = 0; v < r.snapshot->n_vertices(); ++v)
    EXPECT_NEAR(intensity->values[v], 100.0f + 10.0f * r.snapshot->positions[3 * v + 2], 1e-3f);
  // The built-in sphere has none.
  c.scene = "sphere";
  EXPECT_EQ(sim.step(at(0.1, c)).snapshot->field("intensity"), nullptr);
}

TEST(ViewerSimulationDriver, FailedRequestKeepsTheLastGoodMeshWithTheError) {
  std::atomic<int> woken{0};
  SimulationDriver driver([&woken] { ++woken; });
  SimulationControls c = coarse();
  driver.request_step(at(0.0, c, true));
  driver.wait_idle();
  const StepResult good = driver.latest_result();
  ASSERT_TRUE(good.snapshot);
  ASSERT_TRUE(good.error.empty());

  c.scene_parameters = {{"h", -5.0}};
  driver.request_step(at(0.1, c));
  driver.wait_idle();
  const StepResult bad = driver.latest_result();
  EXPECT_FALSE(bad.error.empty());
  EXPECT_EQ(bad.snapshot, good.snapshot);  // the same mesh, not a copy and not nothing
  EXPECT_EQ(driver.results_published(), 2u);
  EXPECT_EQ(woken.load(), 2);
}

TEST(ViewerSimulationDriver, NewestRequestWinsAndARestartIsNotLost) {
  SimulationDriver driver;
  SimulationControls c = coarse();
  driver.request_step(at(0.0, c, true));
  driver.wait_idle();
  driver.request_step(at(0.5, c));
  // Queued behind (or replacing) the step above: a restart, then a plain request.
  driver.request_step(at(0.0, c, true));
  driver.request_step(at(0.1, c));
  driver.wait_idle();
  const StepResult r = driver.latest_result();
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_DOUBLE_EQ(r.snapshot->time, 0.1);
  EXPECT_EQ(r.stats.step, 0u);  // the restart happened, at the newest time
}

}  // namespace
}  // namespace dynamesh
