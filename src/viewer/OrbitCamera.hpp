// The interactive camera: orbit around a pivot, pan, zoom and fly, starting
// from (and reset to) the scene's camera. Produces an rt::Camera for the
// renderer; the up vector stays the scene camera's, so the horizon never rolls.
#pragma once

#include <glm/glm.hpp>
#include <utility>

#include "scene/Scene.hpp"

namespace rt::viewer {

class OrbitCamera {
 public:
  // `home` is the scene's camera; the scene's bounding sphere places the
  // pivot and scales pan, zoom and fly speeds. The camera goes home (and,
  // being new, does not count as changed).
  void setHome(const Camera& home, const WorldPoint& sceneCenter, double sceneRadius);
  void reset();
  // Whether the camera changed in a way the image shows since the last call.
  bool takeChanged() { return std::exchange(changed_, false); }

  const Camera& camera() const { return camera_; }
  const Camera& home() const { return home_; }
  const WorldPoint& pivot() const { return pivot_; }

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
  void lookAt(const WorldPoint& position, const WorldPoint& target);
  // Through a pinhole every focus distance looks the same: only a change
  // of the lens radius, or of the focus of an open lens, counts as changed.
  void setLens(float apertureRadius, float focusDistance);

 private:
  glm::vec3 right() const;
  void placeAtDistance(double distance);
  void move(const glm::dvec3& offset);  // camera and pivot

  Camera home_;
  Camera camera_;
  glm::vec3 worldUp_{0.0f, 1.0f, 0.0f};
  // Positions in the model's double precision: a scene far from the world
  // origin orbits as smoothly as one at it.
  WorldPoint pivot_{0.0};
  WorldPoint homePivot_{0.0};
  double sceneRadius_ = 1.0;
  bool changed_ = false;
};

}  // namespace rt::viewer
