#include "core/adapt/motion_substeps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace dynamesh {

void predict_displacements(const Mesh48& mesh, const SurfaceProbe& probe,
                           const std::vector<Vec3>* rest_points, std::vector<Vec3>& displacement,
                           std::vector<ProjectionStart>* starts) {
  const auto n = static_cast<std::int64_t>(mesh.vertex_capacity());
  displacement.resize(static_cast<std::size_t>(n));
  if (starts) starts->resize(static_cast<std::size_t>(n));
  // A block's vertices are all carried (capsule-bend: three sines and cosines each) before any is
  // evaluated: the block's evaluations then follow one another with nothing between them, and
  // the processor overlaps them. Vertex by vertex, each evaluation waited for its own carry.
  // The same numbers, and on one thread (capsule-bend, the two loops alternating in one
  // process) 7.0-7.5 ms instead of 9.0-10.5 at 10^5 triangles, ~41 instead of ~57 at 10^6.
  constexpr std::int64_t kBlock = 64;
  const std::int64_t blocks = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(dynamic, 16) if (n > kParallelMin)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::int64_t first = b * kBlock, last = std::min(n, first + kBlock);
    Vec3 from[kBlock];
    for (std::int64_t i = first; i < last; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      const auto k = static_cast<std::size_t>(i);
      if (mesh.is_alive(v))
        from[i - first] =
            probe.prediction_from(mesh, v, rest_points ? &(*rest_points)[k] : nullptr);
    }
    for (std::int64_t i = first; i < last; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      const auto k = static_cast<std::size_t>(i);
      if (mesh.is_alive(v))
        displacement[k] =
            probe.predicted_motion_from(mesh, v, from[i - first], starts ? &(*starts)[k] : nullptr);
    }
  }
}

MotionEstimate estimate_substeps(const Mesh48& mesh, const std::vector<Vec3>& displacement,
                                 const SubstepOptions& options) {
  MotionEstimate e;
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  double strain2 = 0.0;  // the largest squared strain: no square root or division per edge
  // An edge can raise the maximum s only if fl(m / l) > s (m = moved2, l = length2); then
  // m / l > s / (1 + u) (u = 2^-53, the unit roundoff), and with low = fl(s kBelow),
  // fl(low l) <= s kBelow (1 + u)^2 l < m for any kBelow <= (1 + u)^-3, about 1 - 3u: every edge
  // that can raise it passes the division-free test low * l < m (a few more than those do,
  // hence the max). So the result is the largest rounded ratio fl(m / l) over the edges, in
  // whatever order they come. The test without the margin (s * l < m, until 2026-11-24) could
  // round against an edge whose ratio rounds just above s, so the maximum depended on which
  // edges came first, i.e. on how the faces were shared out between threads (issue 13).
  // (Assumes low * l is not subnormal: squared lengths and strains far above 1e-300.)
  constexpr double kBelow = 1.0 - 4.0 * std::numeric_limits<double>::epsilon();
  // Each edge once: an interior edge from the face that sees it from its lower vertex id (its
  // other face sees it reversed: the same squared lengths to the bit, since a - b = -(b - a)
  // exactly, so the maximum is the same), a boundary edge from its only face. The twin is in
  // the face's own record, which the corners were just read from.
#pragma omp parallel reduction(max : strain2) if (n > kParallelMin)
  {
    strain2 = 0.0;  // (each thread's; the maximum is at least 0 anyway)
    double low = 0.0;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const Face f(static_cast<std::uint32_t>(i));
      if (!mesh.is_alive(f)) continue;
      const auto v = mesh.vertices(f);
      for (int j = 0; j < 3; ++j) {
        const Vertex a = v[static_cast<std::size_t>(j)],
                     b = v[static_cast<std::size_t>((j + 1) % 3)];
        // (edge j runs from corner j to corner j + 1: the local edge opposite corner j + 2)
        if (a.idx > b.idx && mesh.neighbor(f, (j + 2) % 3).is_valid()) continue;
        const double length2 = (mesh.position(a) - mesh.position(b)).squaredNorm();
        const double moved2 = (displacement[a.idx] - displacement[b.idx]).squaredNorm();
        // False for NaN (ignored, as before); the division only on a candidate maximum, a few
        // times per pass. Edges of no length are skipped; one branch per edge, not two (both
        // tests are taken as one).
        if ((length2 > 0) & (low * length2 < moved2)) {
          strain2 = std::max(strain2, moved2 / length2);
          low = strain2 * kBelow;
        }
      }
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
