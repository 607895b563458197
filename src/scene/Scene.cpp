#include "scene/Scene.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>
#include <type_traits>
#include <utility>
#include <variant>

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

float surfaceArea(const Geometry& geometry, const std::vector<TriangleMesh>& meshes) {
  constexpr float kPi = 3.14159265f;
  const auto triangleArea = [](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // Clamped before the cast: a double beyond float's range is no float.
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    return static_cast<float>(std::min(area, double(std::numeric_limits<float>::max())));
  };
  return std::visit(
      [&](const auto& g) -> float {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Triangle>) {
          return triangleArea(g.v0, g.v1, g.v2);
        } else if constexpr (std::is_same_v<T, Quad>) {
          return triangleArea(g.v0, g.v1, g.v2) + triangleArea(g.v0, g.v2, g.v3);
        } else if constexpr (std::is_same_v<T, Sphere>) {
          return 4.0f * kPi * g.radius * g.radius;
        } else if constexpr (std::is_same_v<T, Cylinder>) {  // side and both caps
          return 2.0f * kPi * g.radius * (2.0f * g.halfHeight) + 2.0f * kPi * g.radius * g.radius;
        } else {
          const TriangleMesh& mesh = meshes.at(g.mesh);
          float area = 0.0f;
          for (const glm::uvec3& f : mesh.faces) {
            const auto placed = [&](uint32_t i) {
              return glm::dvec3(g.objectToWorld * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0));
            };
            area += triangleArea(placed(f.x), placed(f.y), placed(f.z));
          }
          return area;
        }
      },
      geometry);
}

// A Lambertian light of intensity I over area A has radiance
// 2 pi I / (4 pi A) = I / (2 A) (README "Area lights").
bool hasVertexColors(const Geometry& geometry, const std::vector<TriangleMesh>& meshes) {
  const auto* instance = std::get_if<MeshInstance>(&geometry);
  return instance && !meshes.at(instance->mesh).colors.empty();
}

bool addRadianceEmitter(Scene& scene, uint32_t shape, const glm::vec3& radiance) {
  const float area = surfaceArea(scene.shapes.at(shape).geometry, scene.meshes);
  if (!(area > 0.0f)) return false;
  AreaLight light;
  light.shape = shape;
  const glm::dvec3 intensity = 2.0 * double(area) * glm::dvec3(radiance);
  light.diffuseIntensity = light.specularIntensity =
      glm::vec3(glm::min(intensity, glm::dvec3(std::numeric_limits<float>::max())));
  light.profile = EmissionProfile::Lambertian;
  light.samples = 4;
  scene.areaLights.push_back(light);
  return true;
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
