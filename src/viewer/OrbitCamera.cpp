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

glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float degrees) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), axis) * glm::vec4(v, 0.0f));
}

}  // namespace

void OrbitCamera::setHome(const Camera& home, glm::vec3 sceneCenter, float sceneRadius) {
  home_ = home;
  home_.forward = glm::normalize(home.forward);
  worldUp_ = glm::normalize(home.up);
  sceneRadius_ = std::max(sceneRadius, 1e-3f);
  // Orbit around the point on the view axis nearest to the scene's centre,
  // but never around a point behind or right at the camera.
  float depth = glm::dot(sceneCenter - home_.position, home_.forward);
  depth = std::max(depth, 0.25f * sceneRadius_);
  homePivot_ = home_.position + home_.forward * depth;
  reset();
}

void OrbitCamera::reset() {
  camera_ = home_;
  pivot_ = homePivot_;
}

glm::vec3 OrbitCamera::right() const { return cameraBasis(camera_).right; }

void OrbitCamera::placeAtDistance(float distance) {
  camera_.position = pivot_ - camera_.forward * distance;
}

void OrbitCamera::orbit(float yawDegrees, float pitchDegrees) {
  glm::vec3 offset = camera_.position - pivot_;
  // The camera moves to its right when the offset turns towards it: that is a
  // positive rotation about up (up x offset = distance * (forward x up)),
  // and a negative one where image right is up x forward.
  bool mirrored = camera_.imageRight == ImageRight::UpCrossForward;
  offset = rotate(offset, worldUp_, mirrored ? -yawDegrees : yawDegrees);
  glm::vec3 axis = glm::normalize(glm::cross(-offset, worldUp_));
  glm::vec3 pitched = rotate(offset, axis, pitchDegrees);
  if (std::abs(glm::dot(glm::normalize(pitched), worldUp_)) < kMaxUpAlignment) offset = pitched;
  camera_.position = pivot_ + offset;
  camera_.forward = glm::normalize(-offset);
}

void OrbitCamera::pan(glm::vec2 pixels, float imageHeight) {
  float distance = glm::length(pivot_ - camera_.position);
  float tanHalfFov = std::tan(glm::radians(camera_.fovYDegrees) * 0.5f);
  float worldPerPixel = 2.0f * distance * tanHalfFov / std::max(imageHeight, 1.0f);
  glm::vec3 up = cameraBasis(camera_).up;
  // Dragging right moves the scene right, so the camera goes left.
  glm::vec3 move = (-pixels.x * right() + pixels.y * up) * worldPerPixel;
  camera_.position += move;
  pivot_ += move;
}

void OrbitCamera::zoom(float steps) {
  float distance = glm::length(pivot_ - camera_.position);
  float closest = 1e-3f * sceneRadius_;
  placeAtDistance(std::max(distance * std::pow(kZoomPerStep, steps), closest));
}

void OrbitCamera::fly(glm::vec3 sceneRadii) {
  glm::vec3 up = cameraBasis(camera_).up;
  glm::vec3 move =
      (sceneRadii.x * right() + sceneRadii.y * up + sceneRadii.z * camera_.forward) * sceneRadius_;
  camera_.position += move;
  pivot_ += move;
}

void OrbitCamera::lookAt(glm::vec3 position, glm::vec3 target) {
  if (glm::length(target - position) <= 0.0f) return;
  glm::vec3 forward = glm::normalize(target - position);
  if (std::abs(glm::dot(forward, worldUp_)) >= kMaxUpAlignment) return;
  camera_.position = position;
  camera_.forward = forward;
  pivot_ = target;
}

void OrbitCamera::setLens(float apertureRadius, float focusDistance) {
  camera_.apertureRadius = std::max(apertureRadius, 0.0f);
  camera_.focusDistance = std::max(focusDistance, 1e-4f);
  // A lens needs the thin-lens camera; a zero aperture is a pinhole either way.
  if (camera_.apertureRadius > 0.0f) camera_.type = CameraType::ThinLens;
}

}  // namespace rt::viewer
