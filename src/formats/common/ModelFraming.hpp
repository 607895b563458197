// What a model file on its own (glTF, OBJ, PLY) needs to become a scene: a camera
// that frames its geometry and a light when the file brings none, and the
// merge of one file's content into a scene (models inside JSON scenes).
#pragma once

#include <glm/glm.hpp>

#include "scene/Scene.hpp"
#include "scene/SceneBounds.hpp"

namespace rt {

// Fov 45, 800x600, looking at the bounding sphere's centre from above the +z
// side (direction (0, 0.5, 1)), at the distance where the sphere fits.
Camera framingCamera(const WorldBounds& bounds);

// White, intensity 1, above and to the right of the camera (at half the
// camera's distance to the scene centre along each axis), so that surfaces
// facing the camera are lit and shapes show some shading.
PointLight framingLight(const Camera& camera, const WorldBounds& bounds);

// The grey every model scene is drawn on.
constexpr float kModelBackgroundGrey = 0.5f;

// Makes `scene`, which holds only a model's meshes, shapes, materials and
// lights, a scene of its own: the grey background, the framing camera and
// light around its meshes' vertices (the light only if the model brings
// none), textbook conventions (`what` names the file kind for `raytracer
// check`, e.g. "an OBJ file").
void frameModelScene(Scene& scene, const char* what);

// Appends `part`'s materials, textures, meshes, shapes, lights (point and
// area) and warnings to `scene`, shifting the indices that point into its
// lists.
void appendScenePart(Scene& scene, Scene&& part);

}  // namespace rt
