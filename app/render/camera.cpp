#include "app/render/camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace dynamesh {

SceneBounds SceneBounds::from_box(const Box3& box) {
  SceneBounds b;
  if (box.empty()) return b;
  const Vec3 c = box.center();
  b.center = glm::vec3(c.x(), c.y(), c.z());
  b.radius = std::max(1e-6f, static_cast<float>(0.5 * box.diagonal()));
  return b;
}

SceneBounds SceneBounds::from_points(const std::vector<float>& xyz, const Box3& box) {
  SceneBounds b = from_box(box);
  float r2 = 0.0f;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::vec3 d = glm::vec3(xyz[i], xyz[i + 1], xyz[i + 2]) - b.center;
    r2 = std::max(r2, glm::dot(d, d));
  }
  if (r2 > 0.0f) b.radius = std::max(1e-6f, std::sqrt(r2));
  return b;
}

CameraView parse_camera_view(const std::string& text) {
  CameraView v;
  if (text == "fit") return v;
  std::vector<float> numbers;
  std::size_t start = 0;
  for (std::size_t comma; start <= text.size(); start = comma + 1) {
    comma = std::min(text.find(',', start), text.size());
    const std::string word = text.substr(start, comma - start);
    std::size_t used = 0;
    float x = 0.0f;
    try {
      x = std::stof(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (word.empty() || used != word.size() || !std::isfinite(x))
      throw std::invalid_argument("expects fit or AZIMUTH,ELEVATION[,DISTANCE] in degrees, got '" +
                                  text + "'");
    numbers.push_back(x);
  }
  if (numbers.size() < 2 || numbers.size() > 3)
    throw std::invalid_argument("expects fit or AZIMUTH,ELEVATION[,DISTANCE], got '" + text + "'");
  if (std::abs(numbers[1]) > 90.0f)
    throw std::invalid_argument("the elevation must lie in [-90, 90] degrees");
  // The range a saved viewer state may hold (viewer_args.cpp): 1e38 rendered a blank picture.
  if (numbers.size() == 3 && !(numbers[2] >= 1e-4f && numbers[2] <= 1e5f))
    throw std::invalid_argument("the distance must be in [1e-4, 1e5] scene units");
  v.fit = false;
  v.azimuth_deg = numbers[0];
  v.elevation_deg = numbers[1];
  v.distance = numbers.size() == 3 ? numbers[2] : 0.0f;
  return v;
}

glm::quat Camera::rotation_from(float azimuth_deg, float elevation_deg) {
  const glm::quat pitch = glm::angleAxis(glm::radians(elevation_deg), glm::vec3(1, 0, 0));
  const glm::quat yaw = glm::angleAxis(glm::radians(-azimuth_deg), glm::vec3(0, 1, 0));
  return pitch * yaw;
}

glm::quat Camera::default_rotation() {
  // A three-quarter view from slightly above: reads depth better than straight on.
  return rotation_from(CameraView{}.azimuth_deg, CameraView{}.elevation_deg);
}

glm::mat4 Camera::model(const SceneBounds& bounds) const {
  if (!normalize_size) return glm::mat4(1.0f);
  const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / bounds.radius));
  return glm::translate(scale, -bounds.center);
}

glm::mat4 Camera::view() const {
  const glm::mat4 back = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -distance));
  return glm::translate(back * glm::mat4_cast(rotation), -target);
}

glm::mat4 Camera::projection(float aspect, const SceneBounds& bounds) const {
  const SceneBounds b = framed(bounds);
  // Near and far hug the scene for depth precision, wherever the camera is.
  const float to_center = glm::length(glm::vec3(view() * glm::vec4(b.center, 1.0f)));
  const float far_plane = to_center + 2.0f * b.radius + distance;
  const float near_plane = std::max(far_plane * 1e-4f, to_center - 2.0f * b.radius);
  return glm::perspective(glm::radians(fov_y_degrees), aspect, near_plane, far_plane);
}

namespace {

// Point on the unit trackball: a sphere in the middle, a hyperbolic sheet outside, so
// dragging beyond the ball still turns smoothly (about the view axis).
glm::vec3 ball_point(const glm::vec2& p) {
  const float r2 = glm::dot(p, p);
  const float z = r2 <= 0.5f ? std::sqrt(1.0f - r2) : 0.5f / std::sqrt(r2);
  return glm::normalize(glm::vec3(p, z));
}

}  // namespace

void Camera::orbit(const glm::vec2& from_ndc, const glm::vec2& to_ndc) {
  const glm::vec3 a = ball_point(from_ndc);
  const glm::vec3 b = ball_point(to_ndc);
  const glm::vec3 axis = glm::cross(a, b);
  const float len = glm::length(axis);
  if (len < 1e-7f) return;
  const float angle = 2.0f * std::atan2(len, glm::dot(a, b));
  rotation = glm::normalize(glm::angleAxis(angle, axis / len) * rotation);
}

glm::vec2 Camera::half_extent(float aspect) const {
  const float h = distance * std::tan(0.5f * glm::radians(fov_y_degrees));
  return {h * aspect, h};
}

void Camera::pan(const glm::vec2& delta_ndc, float aspect) {
  const glm::vec2 d = delta_ndc * half_extent(aspect);
  target -= glm::inverse(rotation) * glm::vec3(d, 0.0f);
}

void Camera::zoom(float factor, const glm::vec2& cursor_ndc, float aspect) {
  factor = std::clamp(factor, 0.05f, 20.0f);
  // The cursor's point on the target plane is target + R^-1 (offset, 0); moving the
  // target towards it by (1 - factor) keeps it under the cursor as the view shrinks.
  const glm::vec2 offset = cursor_ndc * half_extent(aspect);
  target += (1.0f - factor) * (glm::inverse(rotation) * glm::vec3(offset, 0.0f));
  distance = std::max(1e-6f, distance * factor);
}

SceneBounds Camera::framed(const SceneBounds& bounds) const {
  return normalize_size ? SceneBounds{glm::vec3(0.0f), 1.0f} : bounds;
}

void Camera::fit(const SceneBounds& bounds, float aspect) {
  const SceneBounds b = framed(bounds);
  target = b.center;
  // The bounding sphere fits the narrower of the two field-of-view angles, with a margin.
  const float half_fov_y = 0.5f * glm::radians(fov_y_degrees);
  const float half_fov_x = std::atan(std::tan(half_fov_y) * aspect);
  distance = 1.12f * b.radius / std::sin(std::min(half_fov_x, half_fov_y));
}

void Camera::reset(const SceneBounds& bounds, float aspect) {
  rotation = default_rotation();
  fit(bounds, aspect);
}

void Camera::look(const CameraView& v, const SceneBounds& bounds, float aspect) {
  rotation = rotation_from(v.azimuth_deg, v.elevation_deg);
  fit(bounds, aspect);
  if (!v.fit && v.distance > 0.0f) distance = v.distance;
}

}  // namespace dynamesh
