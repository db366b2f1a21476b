// Orbit camera (GLM): a target point, a distance and a rotation. Trackball orbit, pan in
// the view plane, zoom towards the cursor, fit to the scene, reset. With normalize_size the
// model matrix scales the scene to a unit bounding sphere at the origin, so a surface that
// grows or shrinks over time (the sphere scene: radius 0.6 -> 9) keeps a common size.
// Cursor positions are normalised device coordinates: x, y in [-1, 1], y up.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/geometry/vector_types.h"

namespace dynamesh {

struct SceneBounds {
  glm::vec3 center{0.0f};
  float radius = 1.0f;  // of the bounding sphere; never zero

  static SceneBounds from_box(const Box3& box);
  // Centred on the box, radius reaching the farthest point: tighter than the box's corners.
  static SceneBounds from_points(const std::vector<float>& xyz, const Box3& box);
};

// A view given in numbers (--camera): azimuth and elevation in degrees (azimuth about +y,
// from +z towards +x; elevation above the xz plane, 90 looks straight down), and the
// distance from the scene's centre in scene units (0: fitted to the scene).
struct CameraView {
  bool fit = true;  // "fit": the default three-quarter view, fitted
  float azimuth_deg = 30.0f, elevation_deg = 20.0f;
  float distance = 0.0f;

  bool operator==(const CameraView&) const = default;
};

// "fit", "AZ,EL" or "AZ,EL,DIST". Throws std::invalid_argument saying what is wrong.
CameraView parse_camera_view(const std::string& text);

class Camera {
 public:
  // Plain state, public so the viewer can save and restore it.
  glm::quat rotation = default_rotation();  // world -> view
  glm::vec3 target{0.0f};
  float distance = 3.0f;
  float fov_y_degrees = 35.0f;
  bool normalize_size = false;

  static glm::quat default_rotation();
  // World -> view rotation of a camera at this azimuth and elevation (CameraView).
  static glm::quat rotation_from(float azimuth_deg, float elevation_deg);
  bool operator==(const Camera&) const = default;

  glm::mat4 model(const SceneBounds& bounds) const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect, const SceneBounds& bounds) const;

  // Trackball: the scene turns as if the cursor dragged a ball filling the view.
  void orbit(const glm::vec2& from_ndc, const glm::vec2& to_ndc);
  void pan(const glm::vec2& delta_ndc, float aspect);
  // factor < 1 moves closer; the point under the cursor (on the target's plane) stays put.
  void zoom(float factor, const glm::vec2& cursor_ndc, float aspect);
  // Keeps the rotation, frames the scene.
  void fit(const SceneBounds& bounds, float aspect);
  // Default rotation, then fit.
  void reset(const SceneBounds& bounds, float aspect);
  // The view `v` of the scene: its rotation, framed (or at its distance from the centre).
  void look(const CameraView& v, const SceneBounds& bounds, float aspect);

 private:
  // The scene's bounds in the space the camera looks at (after model()).
  SceneBounds framed(const SceneBounds& bounds) const;
  // Half extents of the view at the target's depth.
  glm::vec2 half_extent(float aspect) const;
};

}  // namespace dynamesh
