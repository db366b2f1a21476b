#include "core/geometry/fold_repair.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/mesh_quality.h"
#include "core/geometry/surface_move.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

Vec3 face_normal(const Mesh48& mesh, Face f) {
  const auto v = mesh.vertices(f);
  const Vec3& a = mesh.position(v[0]);
  return (mesh.position(v[1]) - a).cross(mesh.position(v[2]) - a);
}

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  double smallest = 180.0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
    smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / M_PI);
  }
  return smallest;
}

// Whether the triangle's smallest angle is below the angle whose cosine is `cos_limit` (a
// degenerate triangle is): this runs on every face every step.
bool below_angle(const Vec3& a, const Vec3& b, const Vec3& c, double cos_limit) {
  return smallest_angle_cosine(a, b, c) > cos_limit;
}

// Folded against the surface: the face's normal points away from the surface normal at one
// of its corners.
bool folded_against_surface(const Mesh48& mesh, const Surface& surface, Face f) {
  const Vec3 n = face_normal(mesh, f);
  if (!(n.squaredNorm() > 0)) return true;  // degenerate: no orientation at all
  for (Vertex v : mesh.vertices(f))
    if (n.dot(surface_normal_at(surface, mesh, v)) <= 0) return true;
  return false;
}

// Quality of a face for the repair: its smallest angle in degrees when it is not folded,
// below -1 when it is (so that unfolding always counts as an improvement).
double face_score(const Mesh48& mesh, const Surface& surface, Face f) {
  if (folded_against_surface(mesh, surface, f)) return -1.0;
  const auto v = mesh.vertices(f);
  return smallest_angle_deg(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]));
}

double star_score(const Mesh48& mesh, const Surface& surface, Vertex v) {
  double worst = 180.0;
  mesh.for_each_corner_around(
      v, [&](Corner c) { worst = std::min(worst, face_score(mesh, surface, c.face)); });
  return worst;
}

// Moves v towards its one-ring's centroid (uniform weights: the repair wants well-shaped
// triangles, not the grading the smoothing keeps) in its tangent plane, onto the surface; keeps
// the move (full or half) only if the worst face of its star improves.
bool relax_vertex(Mesh48& mesh, const Surface& surface, Vertex v, std::size_t& failures) {
  if (mesh.is_boundary(v) && surface.kind() == SurfaceKind::kImplicit) return false;
  Vec3 centroid = Vec3::Zero();
  int count = 0;
  mesh.for_each_corner_around(v, [&](Corner c) {
    const auto w = mesh.vertices(c.face);
    centroid += mesh.position(w[static_cast<std::size_t>((c.local + 1) % 3)]) +
                mesh.position(w[static_cast<std::size_t>((c.local + 2) % 3)]);
    count += 2;
  });
  if (count == 0) return false;
  centroid /= count;
  const Vec3 n = surface_normal_at(surface, mesh, v);
  const Vec3 d = centroid - mesh.position(v);
  const Vec3 move = d - d.dot(n) * n;
  const double before = star_score(mesh, surface, v);
  const Vec3 old_position = mesh.position(v);
  const Vec2 old_uv = mesh.uv(v);
  const auto* par = dynamic_cast<const ParametricSurface*>(&surface);
  const auto* imp = dynamic_cast<const ImplicitSurface*>(&surface);
  for (double scale : {1.0, 0.5, 0.25}) {
    Vec3 position = old_position;
    Vec2 uv = old_uv;
    const bool ok = par ? parametric_move(*par, mesh, v, scale * move, uv, position)
                        : implicit_move(*imp, mesh, v, scale * move, position, failures);
    if (!ok) continue;
    mesh.position(v) = position;
    mesh.uv(v) = uv;
    if (star_score(mesh, surface, v) > before) return true;
    mesh.position(v) = old_position;
    mesh.uv(v) = old_uv;
  }
  return false;
}

}  // namespace

namespace {

// 1 folded, 2 sliver, 0 neither: the screen's verdict on one face, given its normal and its
// corners' summed (area-weighted) mesh normals and their lengths.
std::uint8_t verdict(const Mesh48& mesh, const Surface& surface, Face f, const Vec3& fn,
                     const Vec3* corner_normal, const double* corner_norm, double cos_limit) {
  const double half_norm = 0.5 * fn.norm();
  const auto v = mesh.vertices(f);
  bool suspect = !(fn.squaredNorm() > 0);
  for (int c = 0; c < 3; ++c)
    suspect = suspect || fn.dot(corner_normal[c]) <= half_norm * corner_norm[c];
  if (suspect && folded_against_surface(mesh, surface, f)) return 1;
  if (below_angle(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]), cos_limit))
    return 2;
  return 0;
}

}  // namespace

void find_bad_faces(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                    std::vector<Face>& folded, std::vector<Face>& slivers,
                    FoldScreenBuffers* buffers) {
  folded.clear();
  slivers.clear();
  FoldScreenBuffers local;
  FoldScreenBuffers& b = buffers ? *buffers : local;
  // Mesh-only screen: a face turned against its corners' area-weighted mesh normals (more
  // than 60 degrees; a smooth adapted mesh bends far less between neighbours), or below the
  // angle floor. Only those evaluate the surface.
  // Each face's normal once (in parallel), summed into its corners in face order (the sums,
  // hence the verdicts, are those of a serial pass), each vertex normal's length once.
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  const auto nv = static_cast<std::int64_t>(mesh.vertex_capacity());
  b.normal.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (mesh.is_alive(f)) b.normal[static_cast<std::size_t>(i)] = face_normal(mesh, f);
  }
  b.vertex_normal.assign(static_cast<std::size_t>(nv), Vec3::Zero());
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(f)) continue;
    for (Vertex v : mesh.vertices(f))
      b.vertex_normal[v.idx] += b.normal[static_cast<std::size_t>(i)];
  }
  b.vertex_norm.resize(static_cast<std::size_t>(nv));
#pragma omp parallel for schedule(static) if (nv > kParallelMin)
  for (std::int64_t i = 0; i < nv; ++i)
    b.vertex_norm[static_cast<std::size_t>(i)] =
        b.vertex_normal[static_cast<std::size_t>(i)].norm();
  const double cos_limit = std::cos(min_angle_deg * M_PI / 180.0);
  b.kind.assign(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(dynamic, 1024) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(f)) continue;
    const auto v = mesh.vertices(f);
    const Vec3 corner_normal[3] = {b.vertex_normal[v[0].idx], b.vertex_normal[v[1].idx],
                                   b.vertex_normal[v[2].idx]};
    const double corner_norm[3] = {b.vertex_norm[v[0].idx], b.vertex_norm[v[1].idx],
                                   b.vertex_norm[v[2].idx]};
    b.kind[static_cast<std::size_t>(i)] =
        verdict(mesh, surface, f, b.normal[static_cast<std::size_t>(i)], corner_normal, corner_norm,
                cos_limit);
  }
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = b.kind[static_cast<std::size_t>(i)];
    if (k == 1) folded.push_back(Face(static_cast<std::uint32_t>(i)));
    if (k == 2) slivers.push_back(Face(static_cast<std::uint32_t>(i)));
  }
}

void find_bad_faces_around(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                           const std::vector<Vertex>& vertices, std::vector<Face>& folded,
                           std::vector<Face>& slivers) {
  folded.clear();
  slivers.clear();
  // The faces to judge: every live face with a corner in `vertices`, once, in face order.
  std::vector<Face> faces;
  for (Vertex v : vertices)
    if (mesh.is_alive(v))
      mesh.for_each_corner_around(v, [&](Corner c) { faces.push_back(c.face); });
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  // A corner's mesh normal as find_bad_faces sums it: its faces' normals in face order.
  std::vector<Face> ring;
  auto mesh_normal = [&](Vertex v) {
    ring.clear();
    mesh.for_each_corner_around(v, [&](Corner c) { ring.push_back(c.face); });
    std::sort(ring.begin(), ring.end());
    Vec3 sum = Vec3::Zero();
    for (Face f : ring) sum += face_normal(mesh, f);
    return sum;
  };
  const double cos_limit = std::cos(min_angle_deg * M_PI / 180.0);
  for (Face f : faces) {
    const auto v = mesh.vertices(f);
    const Vec3 corner_normal[3] = {mesh_normal(v[0]), mesh_normal(v[1]), mesh_normal(v[2])};
    const double corner_norm[3] = {corner_normal[0].norm(), corner_normal[1].norm(),
                                   corner_normal[2].norm()};
    const std::uint8_t k =
        verdict(mesh, surface, f, face_normal(mesh, f), corner_normal, corner_norm, cos_limit);
    if (k == 1) folded.push_back(f);
    if (k == 2) slivers.push_back(f);
  }
}

FoldReport repair_folds(Mesh48& mesh, const Surface& surface, const FoldRepairOptions& options,
                        FoldScreenBuffers* buffers) {
  FoldReport report;
  if (!options.enabled) return report;
  std::vector<Face> folded, slivers;
  find_bad_faces(mesh, surface, options.min_angle_deg, folded, slivers, buffers);
  report.folded = folded.size();
  report.slivers = slivers.size();
  if (folded.empty() && slivers.empty()) return report;  // the usual case: one pass, no repair
  std::vector<Vertex> active, next;
  std::vector<std::uint32_t> seen(mesh.vertex_capacity(), 0);
  for (const auto* list : {&folded, &slivers})
    for (Face f : *list)
      for (Vertex v : mesh.vertices(f)) active.push_back(v);
  std::size_t failures = 0;
  for (std::uint32_t round = 1;
       round <= static_cast<std::uint32_t>(options.max_rounds) && !active.empty(); ++round) {
    next.clear();
    for (Vertex v : active) {
      if (seen[v.idx] == round) continue;
      seen[v.idx] = round;
      if (relax_vertex(mesh, surface, v, failures)) ++report.moved;
      if (star_score(mesh, surface, v) >= options.min_angle_deg) continue;
      // Still bad: its neighbours relax next round, to make room.
      next.push_back(v);
      mesh.for_each_corner_around(v, [&](Corner c) {
        for (Vertex w : mesh.vertices(c.face))
          if (w != v) next.push_back(w);
      });
    }
    active.swap(next);
  }
  find_bad_faces(mesh, surface, options.min_angle_deg, folded, slivers, buffers);
  report.remaining_folded = folded.size();
  report.remaining_slivers = slivers.size();
  return report;
}

}  // namespace dynamesh
