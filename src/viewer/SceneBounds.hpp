// A bounding sphere of a scene's shapes: places the orbit pivot and scales
// camera speeds and the lens sliders.
#pragma once

#include <glm/glm.hpp>

#include "scene/Scene.hpp"

namespace rt::viewer {

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
};

// For a scene without shapes: a unit sphere in front of its camera.
BoundingSphere boundingSphere(const Scene& scene);

}  // namespace rt::viewer
