// Vertex colours as mesh files give them: sRGB-encoded display values (PLY,
// OBJ) or linear ones (glTF), sometimes out of range, often all white.
#pragma once

#include <glm/vec3.hpp>

#include "scene/Scene.hpp"

namespace rt {

// A colour in [0, 1] per channel (not finite: 0).
glm::vec3 clampedColor(glm::vec3 color);

// An sRGB-encoded colour, clamped to [0, 1], as linear RGB.
glm::vec3 linearFromDisplayColor(glm::vec3 encoded);

// Drops `mesh.colors` when every one is white: multiplying by white changes
// nothing, and without colours the kernels are built without their code.
void dropWhiteColors(TriangleMesh& mesh);

}  // namespace rt
