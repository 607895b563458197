#include "scene/Scene.hpp"

#include <glm/geometric.hpp>
#include <utility>

namespace rt {

CameraBasis cameraBasis(const Camera& camera) {
  glm::vec3 forward = glm::normalize(camera.forward);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  if (camera.imageRight == ImageRight::UpCrossForward) right = -right;
  return {right, up, forward};
}

void setConventions(Scene& scene, Conventions conventions, std::string reason) {
  scene.conventions = conventions;
  scene.conventionsReason = std::move(reason);
  scene.camera.imageRight = conventions == Conventions::CourseworkB ? ImageRight::UpCrossForward
                                                                    : ImageRight::ForwardCrossUp;
}

uint32_t addEmitterShape(Scene& scene, Geometry geometry, std::string label) {
  Material emitter;
  emitter.kd = 0.0f;
  emitter.ks = 0.0f;
  scene.materials.push_back(emitter);
  Shape shape;
  shape.geometry = std::move(geometry);
  shape.material = static_cast<uint32_t>(scene.materials.size() - 1);
  shape.label = std::move(label);
  scene.shapes.push_back(std::move(shape));
  return static_cast<uint32_t>(scene.shapes.size() - 1);
}

void setAreaLightSamples(Scene& scene, uint32_t samples) {
  for (AreaLight& light : scene.areaLights) light.samples = samples;
}

std::optional<Conventions> conventionsNamed(const std::string& name) {
  if (name == "coursework-a") return Conventions::CourseworkA;
  if (name == "coursework-b") return Conventions::CourseworkB;
  if (name == "textbook") return Conventions::Textbook;
  if (name == "physical") return Conventions::Physical;
  return std::nullopt;
}

const char* conventionsName(Conventions conventions) {
  switch (conventions) {
    case Conventions::CourseworkA: return "coursework-a";
    case Conventions::CourseworkB: return "coursework-b";
    case Conventions::Textbook: return "textbook";
    case Conventions::Physical: return "physical";
  }
  return "unknown";
}

SamplerKind samplerUnlessAsked(const RenderSettings& settings, bool progressive) {
  return progressive ? SamplerKind::Sobol : settings.sampler;
}

}  // namespace rt
