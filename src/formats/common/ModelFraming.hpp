// What a model file on its own (glTF, OBJ) needs to become a scene: a camera
// that frames its geometry and a light when the file brings none, and the
// merge of one file's content into a scene (models inside JSON scenes).
#pragma once

#include <glm/glm.hpp>
#include <limits>

#include "scene/Scene.hpp"

namespace rt {

// A world-space box, in double precision: the corners of a placed box may
// not fit a float.
struct ModelBounds {
  glm::dvec3 lo{std::numeric_limits<double>::max()};
  glm::dvec3 hi{std::numeric_limits<double>::lowest()};

  bool empty() const { return lo.x > hi.x; }
  void grow(glm::dvec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : glm::vec3(0.5 * (lo + hi)); }
  float radius() const;
};

// Fov 45, 800x600, looking at the bounding sphere's centre from above the +z
// side (direction (0, 0.5, 1)), at the distance where the sphere fits.
Camera framingCamera(const ModelBounds& bounds);

// White, intensity 1, above and to the right of the camera (at half the
// camera's distance to the scene centre along each axis), so that surfaces
// facing the camera are lit and shapes show some shading.
PointLight framingLight(const Camera& camera, const ModelBounds& bounds);

// The grey every model scene is drawn on.
constexpr float kModelBackgroundGrey = 0.5f;

// Appends `part`'s materials, textures, meshes, shapes, lights and warnings
// to `scene`, shifting the indices that point into its lists.
void appendScenePart(Scene& scene, Scene&& part);

}  // namespace rt
