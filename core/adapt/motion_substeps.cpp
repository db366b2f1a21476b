#include "core/adapt/motion_substeps.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace dynamesh {

void predict_displacements(const Mesh48& mesh, const SurfaceProbe& probe,
                           const std::vector<Vec3>* rest_points, std::vector<Vec3>& displacement,
                           std::vector<ProjectionStart>* starts) {
  const auto n = static_cast<std::int64_t>(mesh.vertex_capacity());
  displacement.resize(static_cast<std::size_t>(n));
  if (starts) starts->resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    if (mesh.is_alive(v))
      displacement[k] = probe.predicted_motion(mesh, v, rest_points ? &(*rest_points)[k] : nullptr,
                                               starts ? &(*starts)[k] : nullptr);
  }
}

MotionEstimate estimate_substeps(const Mesh48& mesh, const std::vector<Vec3>& displacement,
                                 const SubstepOptions& options) {
  MotionEstimate e;
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  double strain2 = 0.0;  // the largest squared strain: no square root or division per edge
  // Every interior edge is seen from both faces: the bound is a maximum, so that is harmless
  // and cheaper than deduplicating.
#pragma omp parallel for schedule(static) reduction(max : strain2) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(f)) continue;
    const auto v = mesh.vertices(f);
    for (int j = 0; j < 3; ++j) {
      const Vertex a = v[static_cast<std::size_t>(j)], b = v[static_cast<std::size_t>((j + 1) % 3)];
      const double length2 = (mesh.position(a) - mesh.position(b)).squaredNorm();
      const double moved2 = (displacement[a.idx] - displacement[b.idx]).squaredNorm();
      // strain2 * length2 < moved2 decides without a division (false for NaN, ignored as
      // before); the division only on a new maximum, a few times per pass. Edges of no length
      // are skipped; one branch per edge, not two (both tests are taken as one).
      if ((length2 > 0) & (strain2 * length2 < moved2)) strain2 = moved2 / length2;
    }
  }
  const double strain = std::sqrt(strain2);
  e.strain = strain;
  if (!options.enabled) return e;
  const double need = strain / options.max_strain;
  // The minimum in double: a need beyond INT_MAX (a vertex Newton sent across a gap) does not
  // convert to int, and came out as INT_MIN sub-steps, i.e. none.
  if (!(need <= 1.0))  // NaN and infinity included
    e.substeps = static_cast<int>(std::isfinite(need)
                                      ? std::min<double>(options.max_substeps, std::ceil(need))
                                      : options.max_substeps);
  return e;
}

}  // namespace dynamesh
