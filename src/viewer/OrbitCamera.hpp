// The interactive camera: orbit around a pivot, pan, zoom and fly, starting
// from (and reset to) the scene's camera. Produces an rt::Camera for the
// renderer; the up vector stays the scene camera's, so the horizon never rolls.
#pragma once

#include <glm/glm.hpp>

#include "scene/Scene.hpp"

namespace rt::viewer {

class OrbitCamera {
 public:
  // `home` is the scene's camera; the scene's bounding sphere places the
  // pivot and scales pan, zoom and fly speeds.
  void setHome(const Camera& home, glm::vec3 sceneCenter, float sceneRadius);
  void reset();

  const Camera& camera() const { return camera_; }
  const Camera& home() const { return home_; }
  glm::vec3 pivot() const { return pivot_; }

  // Degrees around the up axis (positive: the camera moves to its right) and
  // around the camera's right axis (positive: the camera moves down).
  void orbit(float yawDegrees, float pitchDegrees);
  // A mouse drag of `pixels` on an image `imageHeight` pixels tall: the point
  // under the cursor at the pivot's depth follows the cursor.
  void pan(glm::vec2 pixels, float imageHeight);
  // Wheel steps: positive moves towards the pivot.
  void zoom(float steps);
  // Moves camera and pivot by (right, up, forward) * scene radius.
  void fly(glm::vec3 sceneRadii);
  void lookAt(glm::vec3 position, glm::vec3 target);
  void setLens(float apertureRadius, float focusDistance);

 private:
  glm::vec3 right() const;
  void placeAtDistance(float distance);

  Camera home_;
  Camera camera_;
  glm::vec3 worldUp_{0.0f, 1.0f, 0.0f};
  glm::vec3 pivot_{0.0f};
  glm::vec3 homePivot_{0.0f};
  float sceneRadius_ = 1.0f;
};

}  // namespace rt::viewer
