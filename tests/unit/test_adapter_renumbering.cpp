// The adapter through a renumbering of its mesh (Adapter::renumber, AdaptOptions::renumber):
// everything it keeps per element (samples, the predictor's references and rotation, the
// tracker's births, the smoothing workspace's frames, its own start positions) follows, so
// that the steps after a renumbering do what they would have done without it.
//
// The independent check: two adapters run side by side, one renumbered in random order, and
// their meshes are compared as sets of triangles keyed by their corners' coordinates (bit for
// bit), which no numbering enters. Where the adapter's arithmetic does not depend on the
// order of elements (no tangential smoothing: its ring sums add a vertex's faces in id order)
// the two runs must agree exactly, every per-face error and sample included.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>

#include "core/mesh/spatial_order.h"
#include "dense_error.h"
#include "scene_run.h"
#include "tests/support/mesh_validity.h"
#include "tests/support/random_renumbering.h"

namespace dynamesh {
namespace {

using test::start_scene;

// A face by its corners' coordinates, newest vertex first (the storage order is intrinsic).
using FaceKey = std::array<double, 9>;

struct FaceState {
  double error, bound;
  bool measured, densified;
  std::vector<float> samples;  // barycentric coordinates and error, in the face's order
  bool operator==(const FaceState&) const = default;
};

std::map<FaceKey, FaceState> faces_by_position(const Adapter& a) {
  std::map<FaceKey, FaceState> out;
  const Mesh48& mesh = a.mesh();
  for (const Face f : mesh.live_faces()) {
    FaceKey key;
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) key[3 * i + c] = mesh.position(mesh.vertex(f, i))[c];
    FaceState s{a.samples().face_error(f),
                a.predictor().bound(a.samples(), f),
                a.samples().measured(f),
                a.samples().densified(f),
                {}};
    a.samples().for_each_sample(f, [&](const Vec3& b, double e) {
      s.samples.insert(s.samples.end(),
                       {static_cast<float>(b[1]), static_cast<float>(b[2]), static_cast<float>(e)});
    });
    EXPECT_TRUE(out.emplace(key, std::move(s)).second);
  }
  return out;
}

// Stats that no numbering may change (timings and the renumbering flag aside). The mean
// survivor displacement and mean error are sums over vertices / samples in id order: equal
// up to the order of addition.
// `exact`: false where the positions themselves agree to rounding only (smoothing): the
// maxima then agree to rounding too.
void expect_same_stats(const StepStats& a, const StepStats& b, bool exact = true) {
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.splits, b.splits);
  EXPECT_EQ(a.welds, b.welds);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.faces_measured, b.faces_measured);
  EXPECT_EQ(a.vertices_kept, b.vertices_kept);
  EXPECT_EQ(a.kept_fraction, b.kept_fraction);
  const double rounding = exact ? 0.0 : 1e-9;
  EXPECT_NEAR(a.max_error, b.max_error, rounding * a.max_error);
  EXPECT_NEAR(a.survivor_displacement_max, b.survivor_displacement_max,
              rounding * a.survivor_displacement_max);
  const double sums = exact ? 1e-12 : 1e-9;
  EXPECT_NEAR(a.survivor_displacement_mean, b.survivor_displacement_mean,
              sums * a.survivor_displacement_mean);
  EXPECT_NEAR(a.mean_error, b.mean_error, sums * a.mean_error);
  EXPECT_EQ(a.frames_reused, b.frames_reused);
  EXPECT_EQ(a.evaluations_reused, b.evaluations_reused);
  EXPECT_EQ(a.smoothing_moved, b.smoothing_moved);
  EXPECT_EQ(a.substeps, b.substeps);
}

AdaptOptions options(Sampling sampling) {
  AdaptOptions o;
  o.threshold = 1e-3;
  o.epsilon = 2.5e-4;
  o.sampling = sampling;
  o.renumber = false;  // only the test's renumbering
  o.smoothing.enabled = false;
  return o;
}

TEST(AdapterRenumbering, StepsAfterARandomRenumberingAreTheSameExactly) {
  for (const Sampling sampling : {Sampling::kPredictive, Sampling::kFull}) {
    SCOPED_TRACE(sampling == Sampling::kPredictive ? "predictive" : "full");
    auto a = start_scene("capsule-bend", options(sampling), 0.5);
    auto b = start_scene("capsule-bend", options(sampling), 0.5);
    double t = 0.5;
    // A few steps first: the predictor holds references and bounds, the tracker births.
    for (int k = 0; k < 3; ++k) {
      t += 0.004;
      a.adapter->step(t);
      b.adapter->step(t);
    }
    ASSERT_GT(a.adapter->mesh().n_faces(), 5000u);
    std::mt19937 rng(17);
    b.adapter->renumber(random_renumbering(b.adapter->mesh(), rng));
    EXPECT_TRUE(faces_by_position(*a.adapter) == faces_by_position(*b.adapter));
    std::size_t skipped = 0;
    for (int k = 0; k < 6; ++k) {
      SCOPED_TRACE("step " + std::to_string(k + 1) + " after the renumbering");
      t += 0.004;
      const StepStats sa = a.adapter->step(t);
      const StepStats sb = b.adapter->step(t);
      expect_same_stats(sa, sb);
      skipped += sa.triangles - sa.faces_measured;
      ASSERT_TRUE(faces_by_position(*a.adapter) == faces_by_position(*b.adapter));
    }
    if (sampling == Sampling::kPredictive) {
      EXPECT_GT(skipped, 0u);  // the bounds were used
    }
  }
}

// With tangential smoothing a vertex's ring is summed in another order after a renumbering,
// so positions agree to rounding only. Without splits and welds the vertices keep their
// correspondence: each must end where its twin does, and the frames reused (the workspace's
// kept curvature frames, which follow the renumbering) must be the same ones.
TEST(AdapterRenumbering, SmoothingFramesFollowARenumbering) {
  AdaptOptions o = options(Sampling::kPredictive);
  o.smoothing.enabled = true;
  auto a = start_scene("capsule-bend", o, 0.5);
  auto b = start_scene("capsule-bend", o, 0.5);
  o.structural = false;  // from here on: the vertices keep their correspondence
  a.adapter->set_options(o, default_criteria("capsule-bend", 0.0, o, 0.0));
  b.adapter->set_options(o, default_criteria("capsule-bend", 0.0, o, 0.0));
  double t = 0.5;
  for (int k = 0; k < 2; ++k) {
    t += 0.002;
    a.adapter->step(t);
    b.adapter->step(t);
  }
  std::mt19937 rng(23);
  const Renumbering r = random_renumbering(b.adapter->mesh(), rng);
  b.adapter->renumber(r);
  std::size_t reused = 0;
  for (int k = 0; k < 6; ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1) + " after the renumbering");
    t += 0.002;
    const StepStats sa = a.adapter->step(t);
    const StepStats sb = b.adapter->step(t);
    expect_same_stats(sa, sb, false);
    reused += sa.frames_reused;
    double worst = 0;
    for (const Vertex v : a.adapter->mesh().live_vertices())
      worst = std::max(worst, (a.adapter->mesh().position(v) -
                               b.adapter->mesh().position(Vertex(r.vertex[v.idx])))
                                  .norm());
    EXPECT_LT(worst, 1e-9);
  }
  EXPECT_GT(reused, 0u);
}

// The automatic renumbering (AdaptOptions::renumber) at its most eager, renumbering whenever a
// single face is scattered: every frame of a motion is still an embedded manifold within the
// error bound, and the run stays the unrenumbered one's up to rounding.
TEST(AdapterRenumbering, EveryFrameValidWhenRenumberingEveryStep) {
  AdaptOptions o;
  o.threshold = 5e-4;  // ~10,000 vertices: more than one locality window (kLocalityWindow)
  o.epsilon = 1.25e-4;
  AdaptOptions eager = o;
  eager.renumber_scattered_share = 0.0;
  AdaptOptions never = o;
  never.renumber = false;
  auto a = start_scene("capsule-bend", eager, 0.3);
  auto b = start_scene("capsule-bend", never, 0.3);
  EXPECT_TRUE(a.adapter->stats().renumbered);
  EXPECT_FALSE(b.adapter->stats().renumbered);
  int renumbered = 0;
  double t = 0.3;
  for (int k = 0; k < 12; ++k) {
    t += 0.01;
    const StepStats sa = a.adapter->step(t);
    const StepStats sb = b.adapter->step(t);
    SCOPED_TRACE("t = " + std::to_string(t));
    renumbered += sa.renumbered;
    EXPECT_FALSE(sb.renumbered);
    const test::MeshValidity v = test::check_mesh_validity(a.adapter->mesh());
    EXPECT_TRUE(v.embedded_closed_manifold()) << v.describe();
    EXPECT_TRUE(a.adapter->mesh().check().ok());
    const double dense = test::dense_error(a.adapter->mesh(), *a.surface, 2e4, 5).max_error;
    EXPECT_LE(dense, 1.10 * (o.threshold + o.epsilon));
    EXPECT_NEAR(static_cast<double>(sa.triangles), static_cast<double>(sb.triangles),
                0.02 * static_cast<double>(sb.triangles));
    EXPECT_NEAR(sa.kept_fraction, sb.kept_fraction, 0.01);
  }
  EXPECT_GE(renumbered, 10);
  EXPECT_LE(scattered_face_share(a.adapter->mesh()), 0.02);
}

}  // namespace
}  // namespace dynamesh
