#include "scene/ProceduralMesh.hpp"

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rt {

TriangleMesh bumpySphere(const BumpySphereShape& shape) {
  TriangleMesh mesh;
  const uint32_t segments = shape.segments;
  for (uint32_t r = 0; r <= shape.rings; ++r) {
    float theta = glm::pi<float>() * float(r) / float(shape.rings);
    for (uint32_t s = 0; s < segments; ++s) {
      float phi = 2.0f * glm::pi<float>() * float(s) / float(segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                  std::sin(theta) * std::sin(phi));
      float radius =
          1.0f + shape.bump * std::sin(shape.phiWaves * phi) * std::sin(shape.thetaWaves * theta);
      mesh.positions.push_back(radius * n);
      mesh.normals.push_back(n);
    }
  }
  for (uint32_t r = 0; r < shape.rings; ++r) {
    for (uint32_t s = 0; s < segments; ++s) {
      uint32_t a = r * segments + s, b = r * segments + (s + 1) % segments;
      uint32_t c = a + segments, d = b + segments;
      mesh.faces.push_back({a, c, b});
      mesh.faces.push_back({b, c, d});
    }
  }
  return mesh;
}

}  // namespace rt
