#include "app/viewer/uniform_simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "core/surface/projection.h"
#include "core/surface/scene_registry.h"
#include "core/surface/surface_distance.h"

namespace dynamesh {
namespace {

// Splits every face of the coarsest depth, round after round, until the target is reached.
void refine_uniformly(Mesh48& mesh, std::size_t target) {
  while (mesh.n_faces() < target) {
    const std::vector<Face> faces = mesh.live_faces();
    int coarsest = 1 << 30;
    for (Face f : faces) coarsest = std::min(coarsest, mesh.depth(f));
    for (Face f : faces) {
      if (mesh.is_alive(f) && mesh.depth(f) == coarsest) mesh.split(f);
    }
  }
}

double mean_curvature(const Surface& s, const Mesh48& mesh, Vertex v) {
  const PrincipalCurvatures c =
      s.kind() == SurfaceKind::kImplicit
          ? static_cast<const ImplicitSurface&>(s).curvatures(mesh.position(v))
          : static_cast<const ParametricSurface&>(s).curvatures(mesh.uv(v));
  return 0.5 * (c.k1 + c.k2);
}

}  // namespace

void UniformSimulation::rebuild(const SimulationControls& controls) {
  surface_ = make_scene(controls.scene, controls.scene_parameters);
  mesh_ = surface_->base_mesh();
  refine_uniformly(mesh_, std::min<std::size_t>(target_triangles_, controls.max_triangles));
  built_for_ = controls;
}

void UniformSimulation::move_onto_surface() {
  const Surface& s = *surface_;
  for (Vertex v : mesh_.live_vertices()) {
    if (s.kind() == SurfaceKind::kImplicit) {
      const ProjectionResult r =
          project_to_surface(static_cast<const ImplicitSurface&>(s), mesh_.position(v));
      if (r.converged) mesh_.position(v) = r.point;
    } else {
      mesh_.position(v) = static_cast<const ParametricSurface&>(s).position(mesh_.uv(v));
    }
  }
}

std::vector<ScalarField> UniformSimulation::fields() const {
  const Surface& s = *surface_;
  std::vector<ScalarField> out{{"error", std::vector<float>(mesh_.vertex_capacity(), 0.0f)},
                               {"curvature", std::vector<float>(mesh_.vertex_capacity(), 0.0f)},
                               {"valence", std::vector<float>(mesh_.vertex_capacity(), 0.0f)},
                               {"level", std::vector<float>(mesh_.vertex_capacity(), 0.0f)}};
  // Error at each face's centroid, shown at its corners as the largest around them.
  for (Face f : mesh_.live_faces()) {
    const auto vs = mesh_.vertices(f);
    const Vec3 c = (mesh_.position(vs[0]) + mesh_.position(vs[1]) + mesh_.position(vs[2])) / 3.0;
    const double d =
        s.kind() == SurfaceKind::kImplicit
            ? distance_to_surface(static_cast<const ImplicitSurface&>(s), c)
            : distance_to_surface(static_cast<const ParametricSurface&>(s), c,
                                  (mesh_.uv(vs[0]) + mesh_.uv(vs[1]) + mesh_.uv(vs[2])) / 3.0);
    for (Vertex v : vs) out[0].values[v.idx] = std::max(out[0].values[v.idx], float(d));
  }
  for (Vertex v : mesh_.live_vertices()) {
    out[1].values[v.idx] = static_cast<float>(mean_curvature(s, mesh_, v));
    out[2].values[v.idx] = static_cast<float>(mesh_.valence(v));
    out[3].values[v.idx] = static_cast<float>(mesh_.level(v));
  }
  return out;
}

StepResult UniformSimulation::step(const StepRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  StepResult result;
  try {
    const bool same_scene = surface_ && built_for_.scene == request.controls.scene &&
                            built_for_.scene_parameters == request.controls.scene_parameters;
    if (request.restart || !same_scene) rebuild(request.controls);
    surface_->set_time(request.time);
    move_onto_surface();
    auto snapshot = std::make_shared<MeshSnapshot>(make_snapshot(mesh_, nullptr, fields()));
    snapshot->time = request.time;
    StepStatistics& st = result.stats;
    st.triangles = snapshot->n_triangles();
    st.vertices = snapshot->n_vertices();
    const std::vector<float>& e = snapshot->field("error")->values;
    for (float x : e) st.max_error = std::max(st.max_error, double(x));
    for (float x : e) st.mean_error += x / std::max<double>(1.0, double(e.size()));
    result.snapshot = std::move(snapshot);
  } catch (const std::exception& error) {
    result.error = error.what();
  }
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace dynamesh
