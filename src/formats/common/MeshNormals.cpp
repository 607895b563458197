#include "formats/common/MeshNormals.hpp"

#include <vector>

#include "formats/common/UnitVector.hpp"

namespace rt {

void completeVertexNormals(TriangleMesh& mesh) {
  std::vector<glm::vec3>& normals = mesh.normals;
  std::vector<bool> missing(normals.size(), false);
  bool anyMissing = false;
  for (size_t i = 0; i < normals.size(); ++i) {
    missing[i] = !normalizeInPlace(normals[i]);
    anyMissing = anyMissing || missing[i];
    if (missing[i]) normals[i] = glm::vec3(0.0f);
  }
  if (!anyMissing) return;
  for (const glm::uvec3& face : mesh.faces) {
    const glm::vec3& a = mesh.positions[face.x];
    const glm::vec3 weighted = glm::cross(mesh.positions[face.y] - a, mesh.positions[face.z] - a);
    for (int corner = 0; corner < 3; ++corner) {
      if (missing[face[corner]]) normals[face[corner]] += weighted;
    }
  }
  for (size_t i = 0; i < normals.size(); ++i) {
    if (missing[i] && !normalizeInPlace(normals[i])) normals[i] = glm::vec3(0, 0, 1);
  }
}

}  // namespace rt
