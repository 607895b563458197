#include "formats/common/QuadCorners.hpp"

#include <glm/geometric.hpp>

namespace rt {

bool isBowTie(const Quad& quad) {
  const glm::dvec3 first = glm::cross(quad.v1 - quad.v0, quad.v2 - quad.v0);
  const glm::dvec3 second = glm::cross(quad.v2 - quad.v0, quad.v3 - quad.v0);
  return glm::dot(first, second) < 0.0;
}

Quad cornersAroundTheQuad(const Quad& quad) {
  if (!isBowTie(quad)) return quad;
  return {quad.v0, quad.v1, quad.v3, quad.v2};
}

}  // namespace rt
