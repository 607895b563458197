#include "viewer/OrbitCamera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace rt::viewer {
namespace {

// Keeps the view direction this far (cosine) from straight up or down, where
// the right vector (forward x up) would vanish.
constexpr float kMaxUpAlignment = 0.995f;
constexpr float kZoomPerStep = 0.85f;

glm::dvec3 rotate(const glm::dvec3& v, glm::vec3 axis, float degrees) {
  glm::dmat4 rotation =
      glm::rotate(glm::dmat4(1.0), glm::radians(double(degrees)), glm::dvec3(axis));
  return glm::dvec3(rotation * glm::dvec4(v, 0.0));
}

}  // namespace

void OrbitCamera::setHome(const Camera& home, const WorldPoint& sceneCenter, double sceneRadius) {
  home_ = home;
  home_.forward = glm::normalize(home.forward);
  worldUp_ = glm::normalize(home.up);
  sceneRadius_ = sceneRadius > 0.0 ? sceneRadius : 1.0;
  // Orbit around the point on the view axis nearest to the scene's centre,
  // but never around a point behind or right at the camera.
  const glm::dvec3 forward(home_.forward);
  double depth = glm::dot(sceneCenter - home_.position, forward);
  depth = std::max(depth, 0.25 * sceneRadius_);
  homePivot_ = home_.position + forward * depth;
  reset();
  changed_ = false;
}

void OrbitCamera::reset() {
  camera_ = home_;
  pivot_ = homePivot_;
  changed_ = true;
}

glm::vec3 OrbitCamera::right() const { return cameraBasis(camera_).right; }

void OrbitCamera::placeAtDistance(double distance) {
  camera_.position = pivot_ - glm::dvec3(camera_.forward) * distance;
  changed_ = true;
}

void OrbitCamera::move(const glm::dvec3& offset) {
  camera_.position += offset;
  pivot_ += offset;
  changed_ = true;
}

void OrbitCamera::orbit(float yawDegrees, float pitchDegrees) {
  glm::dvec3 offset = camera_.position - pivot_;
  // The camera moves to its right when the offset turns towards it: that is a
  // positive rotation about up (up x offset = distance * (forward x up)),
  // and a negative one where image right is up x forward.
  bool mirrored = camera_.imageRight == ImageRight::UpCrossForward;
  offset = rotate(offset, worldUp_, mirrored ? -yawDegrees : yawDegrees);
  glm::vec3 axis(glm::normalize(glm::cross(-offset, glm::dvec3(worldUp_))));
  glm::dvec3 pitched = rotate(offset, axis, pitchDegrees);
  if (std::abs(glm::dot(glm::normalize(pitched), glm::dvec3(worldUp_))) < kMaxUpAlignment) {
    offset = pitched;
  }
  camera_.position = pivot_ + offset;
  camera_.forward = glm::vec3(glm::normalize(-offset));
  changed_ = true;
}

void OrbitCamera::pan(glm::vec2 pixels, float imageHeight) {
  double distance = glm::length(pivot_ - camera_.position);
  double tanHalfFov = std::tan(glm::radians(double(camera_.fovYDegrees)) * 0.5);
  double worldPerPixel = 2.0 * distance * tanHalfFov / std::max(double(imageHeight), 1.0);
  glm::vec3 up = cameraBasis(camera_).up;
  // Dragging right moves the scene right, so the camera goes left.
  move(glm::dvec3(-pixels.x * right() + pixels.y * up) * worldPerPixel);
}

void OrbitCamera::zoom(float steps) {
  double distance = glm::length(pivot_ - camera_.position);
  double closest = 1e-3 * sceneRadius_;
  placeAtDistance(std::max(distance * std::pow(double(kZoomPerStep), double(steps)), closest));
}

void OrbitCamera::fly(glm::vec3 sceneRadii) {
  glm::vec3 up = cameraBasis(camera_).up;
  glm::vec3 direction = sceneRadii.x * right() + sceneRadii.y * up + sceneRadii.z * camera_.forward;
  move(glm::dvec3(direction) * sceneRadius_);
}

void OrbitCamera::lookAt(const WorldPoint& position, const WorldPoint& target) {
  if (!(glm::length(target - position) > 0.0)) return;
  glm::vec3 forward(glm::normalize(target - position));
  if (std::abs(glm::dot(forward, worldUp_)) >= kMaxUpAlignment) return;
  camera_.position = position;
  camera_.forward = forward;
  pivot_ = target;
  changed_ = true;
}

void OrbitCamera::setLens(float apertureRadius, float focusDistance) {
  const Camera before = camera_;
  camera_.apertureRadius = std::max(apertureRadius, 0.0f);
  // Any positive distance: scenes may be 1e-4 across.
  if (focusDistance > 0.0f) camera_.focusDistance = focusDistance;
  changed_ = changed_ || camera_.apertureRadius != before.apertureRadius ||
             (camera_.apertureRadius > 0.0f && camera_.focusDistance != before.focusDistance);
  // A lens needs the thin-lens camera; a zero aperture is a pinhole either way.
  if (camera_.apertureRadius > 0.0f) camera_.type = CameraType::ThinLens;
}

}  // namespace rt::viewer
