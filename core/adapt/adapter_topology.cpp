// The adapter's topology hooks (issue 16): kept apart from the per-step phases in adapter.cpp.
#include <chrono>

#include "core/adapt/adapter.h"
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
  const TopologyCheck check = topology_->check(implicit);  // once per sub-step
  stats_.topology_events.insert(stats_.topology_events.end(), check.events.begin(),
                                check.events.end());
  stats_.topology_seconds += check.seconds;
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

void Adapter::rebuild_if_folded() {
  const std::size_t folded = stats_.folds_left;  // what repair() could not unfold
  if (folded == 0) return;
  const auto start = std::chrono::steady_clock::now();
  rebuild_from_base();
  topology_->mesh_rebuilt(mesh_);
  stats_.rebuilt = true;
  stats_.folds_repaired += folded;
  stats_.folds_left = 0;
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dynamesh
