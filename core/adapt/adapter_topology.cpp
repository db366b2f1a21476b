// The adapter's topology hooks (issue 16): kept apart from the per-step phases in adapter.cpp.
#include <chrono>

#include "core/adapt/adapter.h"
#include "core/parallel.h"
#include "core/topology/topology_events.h"

namespace dynamesh {

void Adapter::watch_topology() {
  topology_.reset();
  const auto* implicit = dynamic_cast<const ImplicitSurface*>(&surface_);
  if (!options_.topology_events || !implicit || !implicit->may_change_topology()) return;
  topology_ = std::make_unique<TopologyMonitor>();
  topology_->reset(*implicit, mesh_);
}

void Adapter::check_topology() {
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  const TopologyCheck check = topology_->check(implicit);
  stats_.topology_events = check.events;
  stats_.topology_seconds = check.seconds;
  if (!check.rebase) return;
  // No local repair: the whole mesh is rebuilt from F's contour at this time (a global
  // re-base), which the split pass then refines like a first mesh.
  const auto start = std::chrono::steady_clock::now();
  rebuild_from_base();
  topology_->mesh_rebuilt(mesh_);
  stats_.rebuilt = true;
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Adapter::repair_folds() {
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  const auto n = static_cast<std::int64_t>(mesh_.face_capacity());
  std::size_t folded = 0;
#pragma omp parallel for schedule(static) reduction(+ : folded) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (!mesh_.is_alive(f)) continue;
    const auto v = mesh_.vertices(f);
    const Vec3 &a = mesh_.position(v[0]), &b = mesh_.position(v[1]), &c = mesh_.position(v[2]);
    Vec3 g;
    implicit.value_gradient((a + b + c) / 3.0, g);
    folded += !((b - a).cross(c - a).dot(g) > 0);
  }
  if (folded == 0) return;
  const auto start = std::chrono::steady_clock::now();
  rebuild_from_base();
  topology_->mesh_rebuilt(mesh_);
  stats_.rebuilt = true;
  stats_.folds_repaired = folded;
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dynamesh
