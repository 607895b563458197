#include "formats/common/ModelFraming.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace rt {
namespace {
constexpr uint32_t kFramingWidth = 800;
constexpr uint32_t kFramingHeight = 600;
constexpr float kFramingFovDegrees = 45.0f;

// Fov 45, 800x600, looking at the bounding sphere's centre from the +z side,
// at the distance where the sphere fits: from above (direction (0, 0.5, 1)),
// so that an object shows its top, or, for a model that glows, straight on:
// such a model is a lit scene, often a room open at the front (the Cornell
// box), whose ceiling would hide its lamp from above.
Camera framingCamera(const WorldBounds& bounds, bool glows) {
  Camera camera;
  camera.width = kFramingWidth;
  camera.height = kFramingHeight;
  camera.fovYDegrees = kFramingFovDegrees;
  glm::vec3 toCamera = glm::normalize(glm::vec3(0.0f, glows ? 0.0f : 0.5f, 1.0f));
  double distance =
      1.05 * bounds.radius() / std::sin(glm::radians(double(kFramingFovDegrees)) / 2.0);
  camera.position = bounds.center() + glm::dvec3(toCamera) * distance;
  camera.forward = -toCamera;
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  return camera;
}

// White, intensity 1, above and to the right of the camera (at half the
// camera's distance to the scene centre along each axis), so that surfaces
// facing the camera are lit and shapes show some shading.
PointLight framingLight(const Camera& camera, const WorldBounds& bounds) {
  glm::vec3 forward = glm::normalize(camera.forward);
  glm::vec3 right = glm::cross(forward, camera.up);
  if (!(glm::length(right) > 1e-6f)) right = glm::cross(forward, glm::vec3(1.0f, 0.0f, 0.0f));
  if (!(glm::length(right) > 1e-6f)) right = glm::cross(forward, glm::vec3(0.0f, 0.0f, 1.0f));
  right = glm::normalize(right);
  glm::vec3 up = glm::cross(right, forward);
  double distance = glm::length(bounds.center() - camera.position);
  if (!(distance > 0.0)) distance = 1.0;
  WorldPoint position = camera.position + distance * glm::dvec3(0.5f * up + 0.5f * right);
  return {position, glm::vec3(1.0f), glm::vec3(1.0f)};
}

}  // namespace

void frameModel(Scene& scene, const WorldBounds& bounds, const std::optional<Camera>& camera,
                const ModelKind& kind) {
  scene.backgroundColor = glm::vec3(kModelBackgroundGrey);
  scene.camera = camera ? *camera : framingCamera(bounds, !scene.areaLights.empty());
  if (scene.pointLights.empty() && scene.areaLights.empty()) {
    scene.pointLights.push_back(framingLight(scene.camera, bounds));
  }
  if (scene.areaLights.empty() || !kind.glowKey) {
    setConventions(scene, Conventions::Textbook, kind.name);
  } else {
    setConventions(scene, Conventions::Physical,
                   std::string(kind.name) + " whose materials glow (" + kind.glowKey + ")");
  }
}

void frameModelScene(Scene& scene, const ModelKind& kind) {
  WorldBounds bounds;
  for (const TriangleMesh& mesh : scene.meshes) {
    for (const glm::vec3& p : mesh.positions) bounds.grow(glm::dvec3(p));
  }
  frameModel(scene, bounds, std::nullopt, kind);
}

void appendScenePart(Scene& scene, Scene&& part) {
  auto materialBase = static_cast<uint32_t>(scene.materials.size());
  auto meshBase = static_cast<uint32_t>(scene.meshes.size());
  auto textureBase = static_cast<int32_t>(scene.textures.size());
  auto shapeBase = static_cast<uint32_t>(scene.shapes.size());
  for (Material& material : part.materials) {
    if (material.diffuseTexture >= 0) material.diffuseTexture += textureBase;
    scene.materials.push_back(std::move(material));
  }
  for (Shape& shape : part.shapes) {
    shape.material += materialBase;
    if (auto* instance = std::get_if<MeshInstance>(&shape.geometry)) instance->mesh += meshBase;
    scene.shapes.push_back(std::move(shape));
  }
  std::move(part.meshes.begin(), part.meshes.end(), std::back_inserter(scene.meshes));
  std::move(part.textures.begin(), part.textures.end(), std::back_inserter(scene.textures));
  std::move(part.pointLights.begin(), part.pointLights.end(),
            std::back_inserter(scene.pointLights));
  for (AreaLight& light : part.areaLights) {
    light.shape += shapeBase;
    scene.areaLights.push_back(light);
  }
  std::move(part.warnings.begin(), part.warnings.end(), std::back_inserter(scene.warnings));
}

}  // namespace rt
