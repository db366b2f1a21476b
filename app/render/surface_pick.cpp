#include "app/render/surface_pick.h"

#include <limits>

namespace dynamesh {

std::optional<double> ray_triangle(const Vec3& origin, const Vec3& direction, const Vec3& a,
                                   const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14 * e1.norm() * e2.norm() * direction.norm()) return std::nullopt;
  const double inv = 1.0 / det;
  const Vec3 t = origin - a;
  const double u = t.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3 q = t.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double s = e2.dot(q) * inv;
  if (s <= 0.0) return std::nullopt;
  return s;
}

std::optional<Vec3> pick_surface(const MeshSnapshot& mesh, const Camera& camera,
                                 const SceneBounds& bounds, float aspect,
                                 const glm::vec2& cursor_ndc) {
  const glm::mat4 to_clip =
      camera.projection(aspect, bounds) * camera.view() * camera.model(bounds);
  const glm::mat4 to_world = glm::inverse(to_clip);
  const auto unproject = [&](float z) {
    const glm::vec4 h = to_world * glm::vec4(cursor_ndc, z, 1.0f);
    return Vec3(h.x / h.w, h.y / h.w, h.z / h.w);
  };
  const Vec3 origin = unproject(-1.0f), direction = unproject(1.0f) - origin;
  const auto& p = mesh.positions;
  const auto vertex = [&](std::uint32_t v) { return Vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]); };
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const auto s = ray_triangle(origin, direction, vertex(mesh.triangles[t]),
                                vertex(mesh.triangles[t + 1]), vertex(mesh.triangles[t + 2]));
    if (s && *s < nearest) nearest = *s;
  }
  if (!std::isfinite(nearest)) return std::nullopt;
  return Vec3(origin + nearest * direction);
}

}  // namespace dynamesh
