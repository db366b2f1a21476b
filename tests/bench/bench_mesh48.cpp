// Split and weld throughput, single thread, on a mesh of about one million triangles.
// Goal (issue 2): at least 5 million splits and 5 million welds per second.
#include <benchmark/benchmark.h>

#include "core/mesh/base_meshes.h"

namespace dynamesh {
namespace {

void refine_uniformly(Mesh48& mesh) {
  const int depth = mesh.depth(mesh.live_faces().front());
  for (Face f : mesh.live_faces())
    if (mesh.is_alive(f) && mesh.depth(f) == depth) mesh.split(f);
}

// A closed box refined uniformly to 786 432 triangles; one more round gives 1.57 million.
const Mesh48& coarse_mesh() {
  static const Mesh48 mesh = [] {
    Box3 cube;
    cube.extend(Vec3(-1, -1, -1));
    cube.extend(Vec3(1, 1, 1));
    Mesh48 m = make_box_mesh(cube, {16, 16, 16});
    for (int i = 0; i < 8; ++i) refine_uniformly(m);
    return m;
  }();
  return mesh;
}

// Splits every diamond of the ~786k-triangle mesh (393k splits, ending at 1.57M triangles).
void BM_Split(benchmark::State& state) {
  std::int64_t splits = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh48 mesh = coarse_mesh();
    mesh.reserve(2 * mesh.vertex_capacity(), 2 * mesh.face_capacity());
    const std::vector<Face> faces = mesh.live_faces();
    const int depth = mesh.depth(faces.front());
    state.ResumeTiming();
    for (Face f : faces)
      if (mesh.depth(f) == depth) mesh.split(f);
    splits += static_cast<std::int64_t>(faces.size() / 2);
    benchmark::DoNotOptimize(mesh.n_faces());
  }
  state.SetItemsProcessed(splits);
  state.counters["triangles_after"] = static_cast<double>(2 * coarse_mesh().n_faces());
}

// Welds every vertex of the finest level of a 1.57M-triangle mesh back (393k welds).
void BM_Weld(benchmark::State& state) {
  static const Mesh48 fine = [] {
    Mesh48 m = coarse_mesh();
    refine_uniformly(m);
    return m;
  }();
  std::int64_t welds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh48 mesh = fine;
    std::vector<Vertex> finest;
    for (Vertex v : mesh.live_vertices())
      if (mesh.can_weld(v)) finest.push_back(v);
    state.ResumeTiming();
    for (Vertex v : finest) welds += mesh.weld(v);
    benchmark::DoNotOptimize(mesh.n_faces());
  }
  state.SetItemsProcessed(welds);
  state.counters["triangles_before"] = static_cast<double>(fine.n_faces());
}

// Steady state, as during adaptation: the mesh has been refined and welded back before, so
// splits reuse slots from the free lists (no growth, no first touch of fresh memory).
void BM_SplitSteadyState(benchmark::State& state) {
  static const Mesh48 recycled = [] {
    Mesh48 m = coarse_mesh();
    refine_uniformly(m);
    std::vector<Vertex> finest;
    for (Vertex v : m.live_vertices())
      if (m.can_weld(v)) finest.push_back(v);
    for (Vertex v : finest) m.weld(v);
    return m;
  }();
  std::int64_t splits = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh48 mesh = recycled;
    const std::vector<Face> faces = mesh.live_faces();
    const int depth = mesh.depth(faces.front());
    // Copies do not keep free lists' memory warm; one split/weld round trip touches it.
    for (Face f : faces)
      if (mesh.depth(f) == depth) mesh.weld(mesh.split(f));
    state.ResumeTiming();
    for (Face f : faces)
      if (mesh.depth(f) == depth) mesh.split(f);
    splits += static_cast<std::int64_t>(faces.size() / 2);
    benchmark::DoNotOptimize(mesh.n_faces());
  }
  state.SetItemsProcessed(splits);
}

BENCHMARK(BM_Split)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_SplitSteadyState)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Weld)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace dynamesh
