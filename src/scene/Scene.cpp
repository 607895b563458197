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

}  // namespace rt
