// Work a step skips for vertices that barely moved (issue 17): the smoothing's curvature-frame
// reuse (tangential_smoothing.cpp, frame_reusable) and the last fold screen before a frame is
// published, restricted to the faces around changed one-rings (find_bad_faces_around).
// Judged against the same computation without the skip, on a surface whose frames are known
// in closed form (an ellipsoid under a rigid motion of our choosing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/geometry/fold_repair.h"
#include "core/geometry/mesh_quality.h"
#include "core/geometry/surface_move.h"
#include "core/geometry/tangential_smoothing.h"
#include "core/parallel.h"
#include "core/surface/projection.h"
#include "core/surface/scene_registry.h"
#include "scene_run.h"

namespace dynamesh {
namespace {

// F(p) = sum_i (q_i / a_i)^2 - 1 with q = R^T (p - c): an ellipsoid turned by R about c.
class MovedEllipsoid final : public ImplicitSurface {
 public:
  std::string name() const override { return "moved-ellipsoid"; }
  Box3 bounds() const override {
    Box3 box;
    box.extend(centre - Vec3::Constant(1.0));
    box.extend(centre + Vec3::Constant(1.0));
    return box;
  }
  Mesh48 base_mesh() const override { return {}; }
  double value(const Vec3& p) const override {
    const Vec3 q = rotation.transpose() * (p - centre);
    return q.cwiseQuotient(axes).squaredNorm() - 1.0;
  }
  double value_gradient(const Vec3& p, Vec3& gradient) const override {
    const Vec3 q = rotation.transpose() * (p - centre);
    gradient = rotation * Vec3(2.0 * q.cwiseQuotient(axes.cwiseProduct(axes)));
    return q.cwiseQuotient(axes).squaredNorm() - 1.0;
  }
  Mat3 hessian(const Vec3&) const override {
    const Vec3 d = 2.0 * axes.cwiseProduct(axes).cwiseInverse();
    return rotation * d.asDiagonal() * rotation.transpose();
  }

  Vec3 axes{1.0, 0.7, 0.5};
  Mat3 rotation{Mat3::Identity()};
  Vec3 centre{Vec3::Zero()};
};

// The sphere scene's base mesh refined uniformly `levels` times, projected onto `s`.
Mesh48 refined_mesh(const ImplicitSurface& s, int levels) {
  auto sphere = make_scene("sphere");
  Mesh48 mesh = sphere->base_mesh();
  for (int l = 0; l < levels; ++l)
    for (Face f : mesh.live_faces())
      if (mesh.is_alive(f)) mesh.split(f);
  for (Vertex v : mesh.live_vertices())
    mesh.position(v) = project_to_surface(s, mesh.position(v)).point;
  return mesh;
}

// Turns the surface and the mesh rigidly by `angle` about an axis through `pivot`.
void turn(MovedEllipsoid& s, Mesh48& mesh, const Vec3& pivot, double angle) {
  const Mat3 q = Eigen::AngleAxisd(angle, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  s.rotation = q * s.rotation;
  s.centre = pivot + q * (s.centre - pivot);
  for (Vertex v : mesh.live_vertices()) mesh.position(v) = pivot + q * (mesh.position(v) - pivot);
}

double largest_difference(const Mesh48& a, const Mesh48& b) {
  double worst = 0.0;
  for (Vertex v : a.live_vertices())
    worst = std::max(worst, (a.position(v) - b.position(v)).norm());
  return worst;
}

double mean_edge(const Mesh48& mesh) {
  double sum = 0.0;
  std::size_t n = 0;
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    for (int e = 0; e < 3; ++e, ++n)
      sum += (mesh.position(v[e]) - mesh.position(v[(e + 1) % 3])).norm();
  }
  return sum / static_cast<double>(n);
}

// A vertex that does not move while the surface turns about it keeps its place but not its
// frame: the mesh-normal guard must see it, and every frame is then evaluated afresh, so the
// smoothing is bit for bit the one without reuse.
TEST(FrameReuse, SurfaceTurningUnderAStillVertexIsSeen) {
  MovedEllipsoid s;
  Mesh48 mesh = refined_mesh(s, 6);
  SmoothingWorkspace workspace;
  SmoothingOptions o;
  Mesh48 warm = mesh;
  smooth_tangentially(warm, s, o, &workspace);  // every frame cached, at mesh's positions
  // A pivot the rotating fresh evaluation does not pick on the next (second) call.
  Vertex pivot = mesh.live_vertices()[mesh.n_vertices() / 3];
  if ((pivot.idx + 1) % 8 == 0) pivot = mesh.live_vertices()[mesh.n_vertices() / 3 + 1];
  turn(s, mesh, mesh.position(pivot), 0.5);  // ~29 degrees: the pivot stays exactly in place
  Mesh48 reused = mesh, fresh = mesh;
  const SmoothingResult r = smooth_tangentially(reused, s, o, &workspace);
  smooth_tangentially(fresh, s, o);  // no workspace: no reuse
  EXPECT_EQ(r.frames_reused, 0u);
  EXPECT_EQ(largest_difference(reused, fresh), 0.0);
}

// A small motion: most frames are reused (the skip is taken), every vertex is evaluated
// afresh at least every kFrameReuseCalls = 8 calls, and the smoothing differs from the one
// without reuse by what a frame that stale can be off: 8 calls of 2e-4 rad turn, times a
// move of up to about an edge (twice that, for the curvature weights).
TEST(FrameReuse, SmallMotionReusesFramesWithinABoundedDifference) {
  MovedEllipsoid s;
  Mesh48 mesh = refined_mesh(s, 6);
  const std::size_t n = mesh.n_vertices();
  SmoothingWorkspace workspace;
  SmoothingOptions o;
  smooth_tangentially(mesh, s, o, &workspace);
  const double edge = mean_edge(mesh);
  double worst = 0.0;
  std::size_t least = n, most = 0;
  for (int call = 0; call < 16; ++call) {
    turn(s, mesh, Vec3(0.2, 0.1, -0.3), 2e-4);
    Mesh48 fresh = mesh;
    const SmoothingResult r = smooth_tangentially(mesh, s, o, &workspace);
    smooth_tangentially(fresh, s, o);
    worst = std::max(worst, largest_difference(mesh, fresh));
    least = std::min(least, r.frames_reused);
    most = std::max(most, r.frames_reused);
    mesh = fresh;  // the next call starts where the reference is (differences do not add up)
  }
  std::printf("vertices %zu, frames reused per call %zu..%zu, largest difference %.3g edges\n", n,
              least, most, worst / edge);
  EXPECT_GT(least, n / 2);
  EXPECT_LE(most, n - n / 8 + 1);  // the rotating fresh evaluation
  EXPECT_LT(worst, 2.0 * 8 * 2e-4 * edge);
}

// Through the adapter: a twist step reuses most curvature frames, and the predictor takes
// most vertices' F and grad F from the projections that placed them; the accuracy tests
// (PredictiveAnimation, test_predictive_sampling.cpp) run with both.
TEST(FrameReuse, AdapterStepsTakeTheSkips) {
  AdaptOptions o;
  o.threshold = 2e-3;
  o.epsilon = 5e-4;
  test::SceneRun run = test::start_scene("twist", o, 0.5);
  std::size_t frames = 0, evaluations = 0, vertices = 0;
  for (int i = 1; i <= 10; ++i) {
    const StepStats& st = run.adapter->step(0.5 + 1e-3 * i);
    if (i > 1) {
      frames += st.frames_reused;
      evaluations += st.evaluations_reused;
      vertices += st.vertices;
    }
  }
  std::printf("of %zu vertex-steps: frames reused %zu, evaluations reused %zu\n", vertices, frames,
              evaluations);
  EXPECT_GT(static_cast<double>(frames), 0.5 * static_cast<double>(vertices));
  EXPECT_GT(static_cast<double>(evaluations), 0.9 * static_cast<double>(vertices));
  o.smoothing.reuse_frames = false;
  run.adapter->set_options(o, default_criteria("twist", 0.0, o, 0.0));
  EXPECT_EQ(run.adapter->step(0.511).frames_reused, 0u);
}

// A mesh with folds and slivers: random vertices pushed off in random directions.
Mesh48 damaged_mesh(const ImplicitSurface& s, int levels = 5) {
  Mesh48 mesh = refined_mesh(s, levels);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double edge = mean_edge(mesh);
  const std::vector<Vertex> vertices = mesh.live_vertices();
  for (std::size_t i = 0; i < vertices.size(); i += 9)
    mesh.position(vertices[i]) += 0.8 * edge * Vec3(gauss(rng), gauss(rng), gauss(rng));
  return mesh;
}

bool has_corner_in(const Mesh48& mesh, Face f, const std::vector<std::uint8_t>& in) {
  for (Vertex v : mesh.vertices(f))
    if (in[v.idx]) return true;
  return false;
}

// find_bad_faces_around gives find_bad_faces' verdicts on exactly the faces around the
// given vertices: around all of them, the same lists; around a subset, the full lists
// restricted to faces with a corner in it.
TEST(FoldScreenAround, SameVerdictsAsTheFullScreen) {
  MovedEllipsoid s;
  const Mesh48 mesh = damaged_mesh(s);
  std::vector<Face> folded, slivers, folded_around, slivers_around;
  find_bad_faces(mesh, s, 10.0, folded, slivers);
  ASSERT_GT(folded.size(), 10u);
  ASSERT_GT(slivers.size(), 10u);
  find_bad_faces_around(mesh, s, 10.0, mesh.live_vertices(), folded_around, slivers_around);
  EXPECT_EQ(folded_around, folded);
  EXPECT_EQ(slivers_around, slivers);
  std::vector<Vertex> some;
  std::vector<std::uint8_t> in(mesh.vertex_capacity(), 0);
  for (Vertex v : mesh.live_vertices())
    if (v.idx % 5 == 0) {
      some.push_back(v);
      in[v.idx] = 1;
    }
  find_bad_faces_around(mesh, s, 10.0, some, folded_around, slivers_around);
  std::vector<Face> folded_expected, slivers_expected;
  for (Face f : folded)
    if (has_corner_in(mesh, f, in)) folded_expected.push_back(f);
  for (Face f : slivers)
    if (has_corner_in(mesh, f, in)) slivers_expected.push_back(f);
  ASSERT_FALSE(folded_expected.empty());
  EXPECT_EQ(folded_around, folded_expected);
  EXPECT_EQ(slivers_around, slivers_expected);
}

// The screen's angle verdict against an independent measurement: each face's three angles by
// atan2 (no squared cosines, no choice of corner). Every face below the 10-degree floor is
// reported (as a sliver, or as folded, which takes precedence), and every reported sliver is
// below it; away from the floor by 1e-9 degrees, where rounding could go either way. On the
// damaged mesh at two sizes: below kParallelMin faces the screen's passes run fused, above it
// in parallel (the other FoldScreen tests' meshes are all above it).
TEST(FoldScreen, SliversAreTheFacesBelowTheFloorMeasuredIndependently) {
  MovedEllipsoid s;
  for (int levels : {3, 4}) {
    const Mesh48 mesh = damaged_mesh(s, levels);
    std::vector<Face> folded, slivers;
    find_bad_faces(mesh, s, 10.0, folded, slivers);
    std::vector<std::uint8_t> reported(mesh.face_capacity(), 0);
    for (Face f : folded) reported[f.idx] = 1;
    for (Face f : slivers) reported[f.idx] = 2;
    std::size_t below = 0;
    for (Face f : mesh.live_faces()) {
      const auto v = mesh.vertices(f);
      double smallest = 180.0;
      for (int i = 0; i < 3; ++i) {
        const Vec3 u = mesh.position(v[static_cast<std::size_t>((i + 1) % 3)]) -
                       mesh.position(v[static_cast<std::size_t>(i)]);
        const Vec3 w = mesh.position(v[static_cast<std::size_t>((i + 2) % 3)]) -
                       mesh.position(v[static_cast<std::size_t>(i)]);
        smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / M_PI);
      }
      if (smallest < 10.0 - 1e-9) {
        ++below;
        EXPECT_NE(reported[f.idx], 0) << "face " << f.idx << " at " << smallest << " degrees";
      }
      if (reported[f.idx] == 2) {
        EXPECT_LT(smallest, 10.0 + 1e-9) << "face " << f.idx << " reported as a sliver";
      }
    }
    EXPECT_GT(below, 10u) << levels;
    // Each face reported folded is turned against grad F at a corner (value_gradient, not the
    // screen's code), and the screen around every vertex finds the same lists on either path.
    for (Face f : folded) {
      const auto v = mesh.vertices(f);
      const Vec3 n = (mesh.position(v[1]) - mesh.position(v[0]))
                         .cross(mesh.position(v[2]) - mesh.position(v[0]));
      bool against = false;
      for (Vertex u : v) {
        Vec3 g;
        s.value_gradient(mesh.position(u), g);
        against |= n.dot(g) <= 0;
      }
      EXPECT_TRUE(against) << "face " << f.idx << " reported folded";
    }
    EXPECT_GT(folded.size(), 10u) << levels;
    std::vector<Face> folded_around, slivers_around;
    find_bad_faces_around(mesh, s, 10.0, mesh.live_vertices(), folded_around, slivers_around);
    EXPECT_EQ(folded_around, folded) << levels;
    EXPECT_EQ(slivers_around, slivers) << levels;
    const bool parallel = mesh.face_capacity() > static_cast<std::size_t>(kParallelMin);
    EXPECT_EQ(parallel, levels == 4) << mesh.face_capacity();
  }
}

// Through the adapter: publishing after a screen of the changed rings only gives every step
// the same mesh and figures as screening every face.
// The fold screen's scratch kept between calls (FoldScreenBuffers, as the adapter keeps it)
// gives a fresh screen's verdicts whatever it held: here first a larger mesh, then the
// damaged mesh mirrored in x and scaled 1000x (its vertex sums, 10^6 times larger and turned
// against the damaged mesh's own normals, would hide folds and flag sound faces if they
// leaked into the next call's sums).
TEST(FoldScreenBuffersKept, SameVerdictsAsFreshScratch) {
  MovedEllipsoid s;
  const Mesh48 large = refined_mesh(s, 7);
  const Mesh48 damaged = damaged_mesh(s);
  Mesh48 mirrored = damaged;
  for (Vec3& p : mirrored.positions()) p = 1000.0 * Vec3(-p.x(), p.y(), p.z());
  ASSERT_GT(large.face_capacity(), damaged.face_capacity());
  std::vector<Face> folded, slivers, folded_kept, slivers_kept;
  FoldScreenBuffers kept;
  find_bad_faces(large, s, 10.0, folded_kept, slivers_kept, &kept);
  find_bad_faces(mirrored, s, 10.0, folded_kept, slivers_kept, &kept);
  find_bad_faces(damaged, s, 10.0, folded_kept, slivers_kept, &kept);
  find_bad_faces(damaged, s, 10.0, folded, slivers);
  ASSERT_GT(folded.size(), 10u);
  ASSERT_GT(slivers.size(), 10u);
  EXPECT_EQ(folded_kept, folded);
  EXPECT_EQ(slivers_kept, slivers);
  // And back to the larger mesh after the smaller ones.
  find_bad_faces(large, s, 10.0, folded_kept, slivers_kept, &kept);
  find_bad_faces(large, s, 10.0, folded, slivers);
  EXPECT_EQ(folded_kept, folded);
  EXPECT_EQ(slivers_kept, slivers);
  // The screen around vertices, with the same scratch right after the mirrored mesh's (whose
  // corner sums and marks must not leak into the next call) and every vertex listed twice:
  // the full screen's verdicts on the damaged mesh, each face once.
  std::vector<Vertex> twice = damaged.live_vertices();
  const std::vector<Vertex> once = twice;
  twice.insert(twice.end(), once.rbegin(), once.rend());
  find_bad_faces_around(mirrored, s, 10.0, twice, folded_kept, slivers_kept, &kept);
  find_bad_faces_around(damaged, s, 10.0, twice, folded_kept, slivers_kept, &kept);
  find_bad_faces(damaged, s, 10.0, folded, slivers);
  EXPECT_EQ(folded_kept, folded);
  EXPECT_EQ(slivers_kept, slivers);
}

TEST(FoldScreenAround, AdapterStepsMatchTheFullScreen) {
  for (const char* scene : {"capsule-bend", "twist"}) {
    AdaptOptions o;
    o.threshold = 2e-3;
    o.epsilon = 5e-4;
    // Screen after every correction, so that the screen before publishing is the one around
    // the changed rings (small steps skip the first: prescreen_above_strain).
    o.fold_repair.prescreen_above_strain = 0.0;
    test::SceneRun changed = test::start_scene(scene, o, 0.3);
    o.fold_repair.screen_changed_only = false;
    test::SceneRun all = test::start_scene(scene, o, 0.3);
    for (int i = 1; i <= 20; ++i) {
      const double t = 0.3 + 0.01 * i;
      const StepStats a = changed.adapter->step(t);
      const StepStats b = all.adapter->step(t);
      ASSERT_EQ(a.triangles, b.triangles) << scene << " step " << i;
      EXPECT_EQ(a.splits, b.splits);
      EXPECT_EQ(a.welds, b.welds);
      EXPECT_EQ(a.folds_left, b.folds_left);
      EXPECT_EQ(a.slivers_left, b.slivers_left);
      EXPECT_EQ(a.max_error, b.max_error);
      EXPECT_EQ(largest_difference(changed.adapter->mesh(), all.adapter->mesh()), 0.0);
    }
  }
}

// Small steps taken in one go are screened once, before publishing (FoldRepairOptions::
// prescreen_above_strain): every published frame is still judged whole. Twist at 100 steps
// (strains 0.09-0.12, all below the 0.125 bound), its first 40 steps: each frame, measured
// here independently of the screen (the smallest angle from the positions, each face's normal
// against the surface normal at its corners), has no face below 10 degrees and none folded.
TEST(FoldScreenAround, SmallStepsScreenedOnceStillPublishCleanFrames) {
  AdaptOptions o;
  o.threshold = 0.008;
  o.epsilon = o.threshold / 4;
  test::SceneRun run = test::start_scene("twist", o, 0.0);
  int skipped = 0;
  for (int i = 1; i <= 40; ++i) {
    const StepStats& st = run.adapter->step(i / 100.0);
    if (st.substeps == 1 && st.motion_strain <= o.fold_repair.prescreen_above_strain) ++skipped;
    const Mesh48& mesh = run.adapter->mesh();
    EXPECT_GE(measure_quality(mesh).min_angle_deg, 10.0) << "step " << i;
    std::size_t folded = 0;
    for (Face f : mesh.live_faces()) {
      const auto v = mesh.vertices(f);
      const Vec3 n = (mesh.position(v[1]) - mesh.position(v[0]))
                         .cross(mesh.position(v[2]) - mesh.position(v[0]));
      for (Vertex c : v)
        if (!(n.dot(surface_normal_at(*run.surface, mesh, c)) > 0)) {
          ++folded;
          break;
        }
    }
    EXPECT_EQ(folded, 0u) << "step " << i;
  }
  EXPECT_EQ(skipped, 40);  // the path under test was taken
}

}  // namespace
}  // namespace dynamesh
