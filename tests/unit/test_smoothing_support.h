// Drives an Adapter over a scene's animation for the smoothing and quality tests, and
// gathers what they judge: mesh quality (measured by core/geometry/mesh_quality, from
// positions and connectivity only), independent dense error and phase times.
#pragma once

#include <algorithm>
#include <limits>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/adapt/adapter.h"
#include "core/geometry/mesh_quality.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "scene_run.h"

namespace dynamesh::test {

// Faces the geometric error bound speaks for: all of them, except on the multi-criteria
// sphere, where x >= 0 follows an edge length instead (a face with a vertex at x < 0 obeys
// the error criterion; criteria.h).
inline bool error_bounded(const std::string& scene, const Mesh48& mesh, Face f) {
  if (scene != "sphere") return true;
  for (Vertex v : mesh.vertices(f))
    if (mesh.position(v).x() < 0) return true;
  return false;
}

struct AnimationFigures {
  double worst_aspect = 0;    // largest R/(2r) over all steps
  double mean_aspect = 0;     // mean over steps of the mesh's mean R/(2r)
  double p99_aspect = 0;      // mean over steps of the 99th percentile
  double min_angle = 180;     // smallest angle over all steps, degrees
  double mean_min_angle = 0;  // mean over steps of the mean smallest angle per face
  double dense_error = 0;     // largest independent dense error at the checkpoints
  double sampled_error = 0;   // largest adapter (sampled) error over all steps
  double mean_triangles = 0;  // over steps
  std::size_t final_triangles = 0;
  double smooth_seconds = 0, total_seconds = 0;
  std::size_t reverted = 0, moved = 0, splits_refused = 0, pathological_welds = 0;
  double kept_fraction_min = 1;
  bool invariants_ok = true;
};

// `steps` steps from t = 0 to 1; dense error every `dense_every` steps at `dense_density`
// points per unit area (0: none).
inline AnimationFigures animate(const std::string& scene, const AdaptOptions& o, int steps,
                                int dense_every, double dense_density, double t1 = 1.0) {
  AnimationFigures a;
  SceneRun run = start_scene(scene, o);
  for (int i = 1; i <= steps; ++i) {
    const StepStats& s = run.adapter->step(t1 * i / steps);
    const Mesh48& mesh = run.adapter->mesh();
    if (!mesh.check().ok()) a.invariants_ok = false;
    const MeshQuality q = measure_quality(mesh);
    const AspectDistribution d = aspect_distribution(mesh);
    a.worst_aspect = std::max(a.worst_aspect, q.max_aspect);
    a.mean_aspect += q.mean_aspect / steps;
    a.p99_aspect += d.p99 / steps;
    a.min_angle = std::min(a.min_angle, q.min_angle_deg);
    a.mean_min_angle += q.mean_min_angle_deg / steps;
    a.sampled_error = std::max(a.sampled_error, s.max_error);
    a.mean_triangles += static_cast<double>(s.triangles) / steps;
    a.final_triangles = s.triangles;
    a.smooth_seconds += s.seconds.smooth;
    a.total_seconds += s.seconds.total;
    a.moved += s.smoothing_moved;
    a.reverted += s.smoothing_reverted;
    a.splits_refused += s.splits_refused;
    a.pathological_welds += s.pathological_welds;
    a.kept_fraction_min = std::min(a.kept_fraction_min, s.kept_fraction);
    if (dense_every > 0 && i % dense_every == 0) {
      const DenseError e = dense_error(mesh, *run.surface, dense_density, 1000 + i,
                                       [&](Face f) { return error_bounded(scene, mesh, f); });
      a.dense_error = std::max(a.dense_error, e.max_error);
    }
  }
  return a;
}

}  // namespace dynamesh::test
