#include "formats/common/VertexColors.hpp"

#include <algorithm>
#include <cmath>

#include "tone_mapping.h"

namespace rt {

glm::vec3 clampedColor(glm::vec3 color) {
  for (int c = 0; c < 3; ++c)
    color[c] = std::isfinite(color[c]) ? std::clamp(color[c], 0.0f, 1.0f) : 0.0f;
  return color;
}

glm::vec3 linearFromDisplayColor(glm::vec3 encoded) {
  glm::vec3 unit = clampedColor(encoded);
  return {gpu::linearFromSrgb(unit.x), gpu::linearFromSrgb(unit.y), gpu::linearFromSrgb(unit.z)};
}

void dropWhiteColors(TriangleMesh& mesh) {
  const bool allWhite = std::all_of(mesh.colors.begin(), mesh.colors.end(),
                                    [](const glm::vec3& c) { return c == glm::vec3(1.0f); });
  if (allWhite) mesh.colors.clear();
}

}  // namespace rt
