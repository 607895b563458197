// One glTF mesh primitive as an rt::TriangleMesh in its object space.
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "formats/gltf/GltfContext.hpp"
#include "scene/Scene.hpp"

namespace rt::gltf {

// Which TEXCOORD set becomes TriangleMesh::uvs, and the KHR_texture_transform
// applied to it (both come from the material's base colour texture).
struct UvMapping {
  int set = 0;
  glm::mat3 transform{1.0f};
};

// Builds primitive `primitive` of mesh `mesh`: triangles, strips and fans
// become triangles (faces repeating a vertex are dropped); points and lines
// are skipped with a warning, as are primitives left without a triangle.
std::optional<TriangleMesh> buildPrimitive(Context& context, int mesh, int primitive,
                                           const UvMapping& uvMapping);

// The same mesh seen through a mirroring transform: every face's winding is
// reversed so that it stays counter-clockwise (front) in world space.
TriangleMesh mirrored(const TriangleMesh& mesh);

}  // namespace rt::gltf
