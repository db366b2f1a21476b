// The mri scene adapted by the real Adapter: on the synthetic NIfTI ball the layers are
// known spheres; on Colin27 (when mricron-data is installed) the layers at 0, 5, 10 and
// 15 mm must come out as closed manifolds within T + eps under an independent dense
// measurement, coloured by a non-constant intensity.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "core/surface/volume/mri_layers.h"
#include "core/surface/volume/mri_scene.h"
#include "core/surface/volume/mri_surface.h"
#include "dense_error.h"
#include "mesh_measure.h"
#include "test_mri_ball.h"

namespace dynamesh {
namespace {

AdaptOptions mri_options(double threshold) {
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  // The scene's suggestion, scaled to keep the samples per triangle (scene_registry.h).
  o.density = kMriSuggestions.density * kMriSuggestions.threshold / threshold;
  return o;
}

struct MriRun {
  std::unique_ptr<Surface> surface;
  std::unique_ptr<Adapter> adapter;
};

MriRun start(const ParameterOverrides& overrides, const TextOptions& text, const AdaptOptions& o) {
  MriRun run;
  run.surface = make_scene("mri", overrides, text);
  run.adapter = std::make_unique<Adapter>(*run.surface, o, default_criteria("mri", 0.0, o, 0.0));
  run.adapter->initialize();
  return run;
}

void advance(MriRun& run, double t1, int steps) {
  const double t0 = run.surface->time();
  for (int i = 1; i <= steps; ++i) {
    run.adapter->step(t0 + (t1 - t0) * i / steps);
    const CheckReport report = run.adapter->mesh().check();
    ASSERT_TRUE(report.ok()) << "t = " << run.surface->time() << ": " << report.summary();
  }
}

// Closed manifold of sphere topology, measured on the plain triangle list.
void expect_closed_sphere(const Mesh48& mesh, const std::string& where) {
  const test::Topology topo = test::topology(mesh);
  EXPECT_EQ(topo.boundary_edges, 0) << where;
  EXPECT_EQ(topo.euler(), 2) << where;
  EXPECT_GT(test::enclosed_volume(mesh), 0.0) << where;  // oriented outwards
}

// What sparse sampling can miss (as in test_adapter.cpp): the adapter's error comes from
// samples, and a stratified pattern approaches the peak of a triangle's smooth error bump
// within about half a cell, and it measures the first-order distance F / |grad F| where
// that is small. On Colin27 at T = 0.5 mm a dense measurement of every face found up to
// 1.05 (T + eps) at the suggested 2 samples per mm^2 (1.10 at 1 per mm^2, 1.01 at 4); on
// the ball 0.79. 10% is the stated slack.
constexpr double kSparseSamplingSlack = 1.10;

// --- the synthetic ball --------------------------------------------------------------------

TEST(MriAdaptBall, LayersAreClosedSpheresOfRadiusRMinusDWithinTolerance) {
  const AdaptOptions o = mri_options(0.2);
  MriRun run = start({{"depth_max", 10.0}}, {{"volume", test::write_ball_file("mri_adapt")}}, o);
  for (const double t : {0.0, 0.5, 1.0}) {
    if (t > 0) advance(run, t, 5);
    const std::string where = "t = " + std::to_string(t);
    const Mesh48& mesh = run.adapter->mesh();
    const CheckReport report = mesh.check();
    ASSERT_TRUE(report.ok()) << where << ": " << report.summary();
    expect_closed_sphere(mesh, where);

    // 4 points per mm^2: spacing about 0.5 mm, a tenth of the triangles' edges.
    const auto dense = test::dense_error(mesh, *run.surface, 4.0, 17);
    const double bound = (o.threshold + o.epsilon) * kSparseSamplingSlack;
    EXPECT_LE(dense.max_error, bound)
        << where << ": dense error " << dense.max_error << " at (" << dense.worst.transpose()
        << "), " << mesh.n_faces() << " triangles";
    RecordProperty("ball_dense_over_bound_t" + std::to_string(t),
                   std::to_string(dense.max_error / (o.threshold + o.epsilon)));

    // The vertices lie on the layer, itself within half a voxel diagonal of the sphere of
    // radius r = R - d (the resolution of a binary mask, test_mri_surface.cpp). On average
    // the layer lies inside: to first order the boundary blur of MriLayers moves it in by
    // sigma^2 / R and the distance blur by sigma^2 / r, at most 0.34 mm here (measured
    // 0.20-0.26 mm).
    const double r = test::kBallRadius - 10.0 * t;
    double worst = 0.0, sum = 0.0;
    for (const Vertex v : mesh.live_vertices()) {
      const double dr = (mesh.position(v) - test::kBallCentre).norm() - r;
      worst = std::max(worst, std::abs(dr));
      sum += dr;
    }
    const double mean = sum / static_cast<double>(mesh.n_vertices());
    EXPECT_LE(worst, 0.5 * test::kBallSpacing.norm()) << where;
    EXPECT_LE(std::abs(mean), 0.4) << where;
    RecordProperty("ball_mean_radius_error_t" + std::to_string(t), std::to_string(mean));
  }
}

TEST(MriAdaptBall, IntensityFieldFollowsTheVolume) {
  const AdaptOptions o = mri_options(0.5);
  MriRun run = start({{"depth_max", 10.0}}, {{"volume", test::write_ball_file("mri_adapt_i")}}, o);
  // At depth 3 mm every vertex is more than a voxel diagonal (1.8 mm) inside the ball, so
  // the 8 voxels around it hold round(80 + z): trilinear interpolation reproduces the linear
  // 80 + z up to that rounding.
  run.adapter->step(0.3);
  SnapshotFields fields;
  fields.quantities = {"intensity"};
  const MeshSnapshot snap = run.adapter->snapshot(fields);
  const ScalarField* intensity = snap.field("intensity");
  ASSERT_NE(intensity, nullptr);
  ASSERT_EQ(intensity->values.size(), snap.n_vertices());
  double worst = 0.0;
  for (std::size_t i = 0; i < snap.n_vertices(); ++i) {
    const double z = snap.positions[3 * i + 2] - test::kBallCentre.z();
    worst = std::max(worst, std::abs(intensity->values[i] - (80.0 + z)));
  }
  EXPECT_LE(worst, 0.5 + 1e-3);  // + float storage of positions and values
}

// --- the Colin27 brain ----------------------------------------------------------------------

// Faces kept by the dense measurement: every `stride`-th by index, so the test stays fast on
// tens of thousands of triangles while still covering the whole brain.
std::function<bool(Face)> every(std::uint32_t stride) {
  return [stride](Face f) { return f.idx % stride == 0; };
}

TEST(MriAdaptColin27, LayersAt0To15MmAreClosedWithinTolerance) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const AdaptOptions o = mri_options(0.5);
  MriRun run = start({}, {}, o);  // depth_max = 15 mm: depth = 15 t
  SnapshotFields fields;
  fields.quantities = {"intensity"};
  for (const double depth : {0.0, 5.0, 10.0, 15.0}) {
    if (depth > 0) advance(run, depth / 15.0, 5);  // 1 mm per step
    const std::string where = "depth " + std::to_string(depth) + " mm";
    const Mesh48& mesh = run.adapter->mesh();
    const CheckReport report = mesh.check();
    ASSERT_TRUE(report.ok()) << where << ": " << report.summary();
    expect_closed_sphere(mesh, where);

    const auto dense = test::dense_error(mesh, *run.surface, 1.0, 23, every(8));
    const double bound = (o.threshold + o.epsilon) * kSparseSamplingSlack;
    EXPECT_LE(dense.max_error, bound)
        << where << ": dense error " << dense.max_error << " at (" << dense.worst.transpose()
        << "), " << mesh.n_faces() << " triangles";
    RecordProperty("colin_triangles_" + std::to_string(int(depth)), std::to_string(mesh.n_faces()));
    RecordProperty("colin_dense_over_bound_" + std::to_string(int(depth)),
                   std::to_string(dense.max_error / (o.threshold + o.epsilon)));

    // Grey and white matter are crossed along every layer: the colouring must show it.
    const MeshSnapshot snap = run.adapter->snapshot(fields);
    const ScalarField* intensity = snap.field("intensity");
    ASSERT_NE(intensity, nullptr);
    double sum = 0.0, sum2 = 0.0;
    for (const float v : intensity->values) sum += v, sum2 += double(v) * v;
    const double n = static_cast<double>(intensity->values.size());
    const double sd = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
    const Vec2 window = dynamic_cast<const MriSurface&>(*run.surface).intensity_window();
    EXPECT_GT(sd, 0.05 * (window[1] - window[0])) << where;
    RecordProperty("colin_intensity_sd_" + std::to_string(int(depth)), std::to_string(sd));
  }
}

}  // namespace
}  // namespace dynamesh
