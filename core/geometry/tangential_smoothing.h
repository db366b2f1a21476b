// Curvature-sensitive tangential smoothing: Equation 1 of de Goes et al. 2006 (Section 3.3).
//
// Each vertex p moves on its tangent plane towards the centroid c of its one-ring,
//   v = p - c,  d = v - <v, n> n,
//   p <- p - <u1, d> exp(-k l1) u1 - <u2, d> exp(-k l2) u2,
// with u_i, l_i the principal directions and curvature magnitudes of S at p, and is then
// brought back onto S. (The paper prints "p + ..." with v = p - c; the intent, and the
// authors' code, is a move towards c.) Large k keeps vertices across ridges; k = 0 is plain
// tangential Laplacian smoothing. By default l_i is |k_i| normalised to [0, 1] by the
// mesh-wide range, as the original implementation does, so k means the same at any scale.
//
// Parametric surfaces move in (u, v) through the pseudo-inverse of the Jacobian [Su Sv];
// implicit ones move in space and are projected by Newton steps. Guards: a move that flips a
// triangle against the surface normal or pushes its smallest angle below min_angle_deg (and
// below what it was) is undone for that vertex; parameter-domain boundary vertices slide only
// along their side and the domain's corners stay put; other open-boundary vertices stay put.
// An implicit family that never moves its points along some axis (ImplicitSurface::
// invariant_axis, the twist) gets moves without a component along it (the projection back
// onto S may still change it slightly, as the normal correction does). A vertex already
// within SmoothingOptions::settled_offset of an edge of its centroid may be left in place (a
// departure from the paper, a solver's tolerance; off by default: below).
#pragma once

#include <cstddef>
#include <memory>

#include "core/mesh/mesh48.h"
#include "core/surface/projection.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct SmoothingOptions {
  bool enabled = true;
  double k = 2.0;              // curvature sensitivity (the paper's constant k)
  int iterations = 1;          // per step
  bool raw_curvature = false;  // true: l_i = |k_i| in scene units (k then has units of length)
  double min_angle_deg = 5.0;  // guard
  // Centroid weights: inverse edge length (keeps the 4-8 mesh's grading; default) or
  // uniform (the paper's plain one-ring centroid).
  bool scale_invariant_weights = false;
  // With a workspace kept from step to step: reuse a vertex's curvature frame while it and
  // the surface under it barely moved (the bound is in tangential_smoothing.cpp,
  // frame_reusable); false evaluates every frame every iteration.
  bool reuse_frames = true;
  // A vertex whose tangential offset from its ring centroid (Equation 1's |d|) is below this
  // fraction of its ring's mean edge length has settled: it is left where it is, without a
  // move or a projection. The relaxation then rests within that distance of Equation 1's
  // fixed point instead of chasing it by ever smaller moves (each still a projection onto S),
  // and follows it as soon as the offset grows past it; the offset, not the move, is what
  // counts, so a vertex held on a ridge by a large k still creeps as the paper's does.
  // 0 (the default): every vertex moves every iteration, as in the paper. 0.01 takes 11-16% off
  // a capsule-bend step at 10^6 triangles (86% of the vertices settled), but is not the default
  // yet: four tests of the paper's smoothing fail with it (README, "Settled vertices").
  double settled_offset = 0.0;
  // On a surface with a rest map, each vertex's rest-space point where the caller knows it
  // (by vertex id): the adapter's, from which it carried the vertices in this step (their
  // projection afterwards removes rounding and drift only, far below the reuse test's 0.05 of
  // an edge). Frame reuse then reads it instead of mapping every vertex back (a bend map's
  // atan2 and square root per vertex). Null: mapped back.
  const std::vector<Vec3>* rest_points = nullptr;
  // Implicit surfaces: F and grad F already evaluated where the vertices are, on the surface as
  // it is now, where the caller knows them (by vertex id; an entry counts where its point is
  // the vertex's position and its epoch is `evaluations_epoch`): the adapter's normal
  // correction leaves them. Such a vertex's move is projected from its second-order landing
  // point (second_order_landing, surface_move.h): one evaluation where the move from p + move
  // took a Newton step and two (1.76 a move at 10^6 triangles, capsule-bend). Null: from
  // p + move. Either way the vertex lands on S within the projection's tolerance.
  const std::vector<PointEvaluation>* evaluations = nullptr;
  std::uint64_t evaluations_epoch = 0;
};

struct SmoothingResult {
  std::size_t moved = 0;     // vertex moves kept (summed over iterations)
  std::size_t reverted = 0;  // moves undone by the guards
  std::size_t projection_failures = 0;
  std::size_t frames_reused = 0;  // curvature frames reused instead of evaluated
};

// Scratch buffers of smooth_tangentially, kept by a caller that smooths every step so that
// a step reuses their memory instead of allocating (and page-faulting) it anew, and the
// curvature frames of vertices that barely moved (SmoothingOptions::reuse_frames). Listen to
// the mesh's splits (a new vertex may carry a freed id) and renumberings; forget_frames()
// when the mesh is replaced.
class SmoothingWorkspace final : public MeshListener {
 public:
  SmoothingWorkspace();
  ~SmoothingWorkspace() override;
  void forget_frames();
  // Implicit surfaces: F and grad F where the last call moved v, if it did (its projection's
  // last evaluation; false for a vertex it left in place).
  bool landed(Vertex v, double& value, Vec3& gradient) const;
  void after_split(Mesh48& mesh, const DiamondChange& change) override;
  void after_weld(Mesh48&, const DiamondChange&) override {}
  // The kept frames (and where the last call moved each vertex) move to the new ids; the
  // other buffers are rebuilt by every call.
  void after_renumber(Mesh48& mesh, const Renumbering& renumbering) override;
  SmoothingWorkspace(const SmoothingWorkspace&) = delete;
  SmoothingWorkspace& operator=(const SmoothingWorkspace&) = delete;
  struct Buffers;
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

SmoothingResult smooth_tangentially(Mesh48& mesh, const Surface& surface,
                                    const SmoothingOptions& options,
                                    SmoothingWorkspace* workspace = nullptr);

}  // namespace dynamesh
