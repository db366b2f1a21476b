// Picking: the point of the mesh on screen under the cursor, found on the CPU by casting the
// cursor's ray through the snapshot's triangles (the nearest hit wins). Used by the viewer's
// "what is here?" probe (issue 14); same camera maths as the renderer, so what is hit is
// what is drawn there.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "app/render/camera.h"
#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

// `cursor_ndc`: normalised device coordinates of the view (x, y in [-1, 1], y up); `aspect`
// its width / height. nullopt when the ray misses the mesh.
std::optional<Vec3> pick_surface(const MeshSnapshot& mesh, const Camera& camera,
                                 const SceneBounds& bounds, float aspect,
                                 const glm::vec2& cursor_ndc);

// The ray's hit with triangle (a, b, c) at origin + s * direction, s > 0 (Moeller and
// Trumbore, "Fast, minimum storage ray-triangle intersection", 1997); nullopt when missed.
std::optional<double> ray_triangle(const Vec3& origin, const Vec3& direction, const Vec3& a,
                                   const Vec3& b, const Vec3& c);

}  // namespace dynamesh
