// Topology events of a deforming implicit surface, found from F (issue 16, event detection),
// and the decision to rebuild the mesh.
//
// Every step the monitor samples F and grad F on a coarse grid over the surface's bounds:
//  - F's critical points (critical_points.h) are matched to those of the previous step (same
//    Morse index, nearest); one whose value changed sign is an event, at the time where the
//    value crosses zero by linear interpolation over the step, of a kind given by its index
//    and the direction of the crossing (a saddle of index 1 going negative joins two parts of
//    the inside: a merge; going positive, a pinch or split; and so on);
//  - a safety net contours the same grid (marching tetrahedra) and compares its Euler
//    characteristic and number of components with the mesh's: a mismatch the critical points
//    did not explain is reported as an event of kind "mismatch" at the current time, placed at
//    the centre of the bounds (the net does not locate it).
// The grid's contour is piecewise linear: within about half the Hessian times a cell diagonal
// squared of a critical point's value it may already show (or still miss) the crossing -- two
// blobs joined through one tetrahedron before they touch, a new neck thinner than a cell. While
// a critical point is that close to zero the contour is not trusted: the net stays silent, and
// what the mesh must become is the Euler characteristic Morse theory gives for the events
// (`expected_euler`; an i-handle changes the surface's characteristic by 2 (-1)^i). Otherwise
// the contour's topology is what the mesh must have. The mesh is changed (`rebase`) when an event
// happened or a trusted contour disagrees with it.
//
// A surface whose critical points are fixed (FixedCriticalField: F = G + c(t), mri) is watched
// without a grid: its critical points, those of persistence below `resolution` cancelled, are
// sorted by G, and a step's events are those whose -G lies between c at the step's two ends
// (a binary search). No contour is compared (a 24-cell grid cannot resolve a brain's folds, and
// what it misses is below the resolution by construction): the mesh must then have the Euler
// characteristic Morse theory gives, and a monitor that has no point to watch (`idle`) is not
// kept by the adapter.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"
#include "core/topology/contour_base_mesh.h"
#include "core/topology/critical_points.h"
#include "core/topology/fixed_critical_points.h"
#include "core/topology/topology_event.h"

namespace dynamesh {

// Euler characteristic and number of connected components of a closed mesh.
struct MeshTopologySummary {
  long euler = 0;
  long components = 0;
  bool operator==(const MeshTopologySummary&) const = default;
};
MeshTopologySummary summarize_topology(const Mesh48& mesh);
MeshTopologySummary summarize_topology(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                       std::size_t vertex_count);
// The piece of each of `vertex_count` vertices, pieces joined through `triangles` and numbered
// 0 ... count - 1 in the order of their lowest vertex (a vertex in no triangle is a piece).
std::vector<std::uint32_t> vertex_pieces(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                         std::size_t vertex_count, std::size_t& count);
// The same for a mesh's live faces, over its vertex slots (dead ones are pieces of their own).
std::vector<std::uint32_t> vertex_pieces(const Mesh48& mesh, std::size_t& count);
// A mesh's live faces as vertex id triples, in Mesh48::live_faces() order.
std::vector<std::array<std::uint32_t, 3>> live_triangles(const Mesh48& mesh);

struct TopologyCheck {
  std::vector<TopologyEvent> events;
  bool rebase = false;          // the mesh's topology must change
  MeshTopologySummary contour;  // of F's zero set on the grid, now
  bool contour_trusted = true;  // no critical point within the grid's resolution of F = 0
  long expected_euler = 0;      // the mesh's, changed by the events (Morse theory)
  double seconds = 0.0;         // what the check cost
};

class TopologyMonitor {
 public:
  // `resolution`: pairs of fixed critical points closer in value than this are cancelled (the
  // mesh's error bound T; fixed_critical_points.h).
  explicit TopologyMonitor(const ContourBaseOptions& grid = {}, double resolution = 0.0);

  // The mesh was (re)built for the surface at its current time.
  void reset(const ImplicitSurface& surface, const Mesh48& mesh);
  // The surface has moved on to its current time since the last reset() or check().
  TopologyCheck check(const ImplicitSurface& surface);
  // The mesh was rebuilt after a check() (its critical points are already current).
  void mesh_rebuilt(const Mesh48& mesh) { mesh_topology_ = summarize_topology(mesh); }
  // F's critical points found at the last reset() or check() (fixed ones: all of them).
  const std::vector<CriticalPoint>& critical_points() const { return previous_; }
  // The watching grid's spacing (its largest cell side) at the last reset() or check().
  double spacing() const { return spacing_; }
  // Watching a surface with fixed critical points of which none lies in its animation's range:
  // its topology cannot change.
  bool idle() const { return fixed_ != nullptr && fixed_->points.empty(); }
  // The fixed critical points watched (nullptr: a grid is searched every step).
  const FixedCriticalPoints* fixed_points() const { return fixed_; }
  // A level L for a re-base's contour of F = L (ContourBaseOptions::level) on a grid of cell
  // diagonal `diagonal`: every critical point found at the last check keeps its side, F - L
  // of the sign of F, by at least `fraction` of the bound within which that grid's
  // piecewise-linear contour may be wrong about it (|Hess F| diagonal^2 / 2). The L nearest 0;
  // none when two critical points ask for opposite sides.
  // Only the critical points within `within`, when given (a local patch's grid).
  std::optional<double> clear_level(double diagonal, double fraction,
                                    const Box3* within = nullptr) const;

 private:
  ContourGrid grid_for(const ImplicitSurface& surface) const;
  TopologyCheck check_fixed(const FixedCriticalField& field, double time);

  ContourBaseOptions grid_options_;
  double resolution_ = 0.0;
  const FixedCriticalPoints* fixed_ = nullptr;  // owned by the surface
  double previous_offset_ = 0.0;
  std::vector<CriticalPoint> previous_;
  double previous_time_ = 0.0;
  MeshTopologySummary mesh_topology_;
  double spacing_ = 0.0;
  double diagonal_ = 0.0;  // of the watching grid's cells: which side a critical point is on
};

}  // namespace dynamesh
