// Motion in proportion to the mesh: how many sub-steps a step needs so that no vertex moves
// too far against its neighbours in one go (a CFL-like bound, DESIGN.md "Quality bars": every
// frame, whatever the step size).
//
// Each vertex's predicted displacement d over the step comes from the surface (SurfaceProbe::
// predicted_motion_from): parametric S(u, v, t1) - p; carried along a rest map; otherwise the
// normal velocity v = -F grad F / |grad F|^2 integrated over the step. The bound is the
// largest edge strain |d_a - d_b| / |a - b|: how far an edge turns or stretches in one go,
// relative to its length. A rigid motion gives 0, so a translating or rotating surface costs
// no sub-steps; a growing sphere costs log-many (its edges stretch by the radius' ratio); a
// twist or an isolayer sinking towards its creases costs sub-steps where its edges turn.
// (Bounding the displacement against the edge length as well -- |d| / |e| -- was tried and
// dropped: it cut a growing sphere's steps into 19 sub-steps where 2 keep every frame clean,
// and added nothing on twist or mri.) The step is cut into n equal sub-steps so that the
// strain of each stays within the limit.
#pragma once

#include <vector>

#include "core/adapt/surface_probe.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {

struct SubstepOptions {
  bool enabled = true;
  double max_strain = 0.25;  // largest |d_a - d_b| / |a - b| per sub-step
  int max_substeps = 32;
};

struct MotionEstimate {
  double strain = 0.0;  // over the whole step
  int substeps = 1;
};

// `displacement[v]`: predicted motion of every live vertex over the step (others ignored).
MotionEstimate estimate_substeps(const Mesh48& mesh, const std::vector<Vec3>& displacement,
                                 const SubstepOptions& options);

// Fills `displacement` with every live vertex's predicted motion to the surface's current
// time (rest_points: recorded before the time changed, for surfaces that follow the material;
// else null), in parallel. `starts` (may be null; implicit surfaces): each vertex's
// SurfaceProbe::predicted_motion_from start, for the projection that follows at the same time.
void predict_displacements(const Mesh48& mesh, const SurfaceProbe& probe,
                           const std::vector<Vec3>* rest_points, std::vector<Vec3>& displacement,
                           std::vector<ProjectionStart>* starts = nullptr);

}  // namespace dynamesh
