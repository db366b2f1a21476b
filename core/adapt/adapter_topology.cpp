// The adapter's topology hooks (issue 16): kept apart from the per-step phases in adapter.cpp.
#include <algorithm>
#include <chrono>

#include "core/adapt/adapter.h"
#include "core/topology/local_repair.h"
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
  // Locally first; when that cannot be done the whole mesh is rebuilt from F's contour at this
  // time (a global re-base), which the split pass then refines like a first mesh.
  const auto start = std::chrono::steady_clock::now();
  if (!repair_topology_locally(check)) {
    rebuild_from_base();
    stats_.rebuilt = true;
  }
  topology_->mesh_rebuilt(mesh_);
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool Adapter::repair_topology_locally(const TopologyCheck& check) {
  if (!options_.local_topology_repair) return false;
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  // The cut reaches two cells of the watching grid around the critical point (the mesh is
  // wrong within about one: the event happened since the last step), the patch is contoured
  // at the seam's edge size, between half a cell and three quarters of one (local_repair.h;
  // a whole cell left the narrow blobs' new neck faces so large that their sparse samples
  // missed the error next to it: dense error 1.11 (T + eps) in the step after the merge).
  LocalRepairOptions o;
  o.radius = 2.0 * topology_->spacing();
  o.spacing = 0.5 * topology_->spacing();
  o.max_spacing = 0.75 * topology_->spacing();
  std::size_t repaired = 0;
  for (const TopologyEvent& e : check.events) {
    if (e.kind == TopologyEventKind::kMismatch) return false;  // not located
    const LocalRepairResult r = repair_locally(mesh_, implicit, e.position, o);
    if (!r.repaired) {
      stats_.repair_refusals.push_back(r.why_not);
      continue;
    }
    ++repaired;
    stats_.repair_faces_replaced += r.removed_faces;
    stats_.repair_spacing = std::max(stats_.repair_spacing, r.spacing);
    adopt_repair(r.new_vertices);
  }
  if (repaired == 0) return false;
  stats_.local_repairs += repaired;
  return summarize_topology(mesh_) == check.contour;
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
