#include "viewer/SceneBounds.hpp"

#include <algorithm>
#include <limits>
#include <variant>

namespace rt::viewer {
namespace {

struct Box {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{std::numeric_limits<float>::lowest()};
  void add(glm::vec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void add(glm::vec3 center, float radius) {
    add(center - glm::vec3(radius));
    add(center + glm::vec3(radius));
  }
  bool empty() const { return min.x > max.x; }
};

void addShape(const Scene& scene, const Geometry& geometry, Box& box) {
  std::visit(
      [&](const auto& g) {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Sphere>) box.add(g.center, g.radius);
        if constexpr (std::is_same_v<T, Triangle>) {
          for (glm::vec3 v : {g.v0, g.v1, g.v2}) box.add(v);
        }
        if constexpr (std::is_same_v<T, Quad>) {
          for (glm::vec3 v : {g.v0, g.v1, g.v2, g.v3}) box.add(v);
        }
        if constexpr (std::is_same_v<T, Cylinder>) box.add(g.center, g.radius + g.halfHeight);
        if constexpr (std::is_same_v<T, MeshInstance>) {
          if (g.mesh >= scene.meshes.size()) return;
          for (glm::vec3 p : scene.meshes[g.mesh].positions) {
            box.add(glm::vec3(g.objectToWorld * glm::vec4(p, 1.0f)));
          }
        }
      },
      geometry);
}

}  // namespace

BoundingSphere boundingSphere(const Scene& scene) {
  Box box;
  for (const Shape& shape : scene.shapes) addShape(scene, shape.geometry, box);
  if (box.empty()) return {scene.camera.position + glm::normalize(scene.camera.forward), 1.0f};
  glm::vec3 center = 0.5f * (box.min + box.max);
  float radius = 0.5f * glm::length(box.max - box.min);
  return {center, std::max(radius, 1e-3f)};
}

}  // namespace rt::viewer
