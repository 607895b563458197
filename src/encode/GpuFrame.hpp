// The GPU's coordinates: world positions relative to a frame origin (the
// camera's position when the scene is encoded), subtracted in double
// precision and only then rounded to float. A scene far from the world
// origin is thus resolved as finely as one at the origin.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/Scene.hpp"

namespace rt {

struct GpuFrame {
  WorldPoint origin{0.0};

  glm::vec3 point(const WorldPoint& p) const { return glm::vec3(p - origin); }
  // `objectToWorld` followed by the move into the frame, rounded once.
  glm::mat4 transform(const WorldTransform& objectToWorld) const {
    return glm::mat4(glm::translate(WorldTransform(1.0), -origin) * objectToWorld);
  }
};

}  // namespace rt
