// Vertex normals as mesh files give them: of any length, and zero (or
// missing) where the writer had none.
#pragma once

#include "scene/Scene.hpp"

namespace rt {

// Makes every normal of `mesh` unit length; the zero and non-finite ones
// become the area-weighted normal of the faces around their vertex.
void completeVertexNormals(TriangleMesh& mesh);

}  // namespace rt
