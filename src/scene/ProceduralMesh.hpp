// Generated meshes for tests and benchmarks: sizes and shapes on demand,
// without files.
#pragma once

#include <cstdint>

#include "scene/Scene.hpp"

namespace rt {

struct BumpySphereShape {
  uint32_t rings = 24;     // latitude bands
  uint32_t segments = 32;  // longitude steps
  float bump = 0.08f;      // radius 1 + bump * sin(phiWaves * phi) * sin(thetaWaves * theta)
  float phiWaves = 5.0f;
  float thetaWaves = 4.0f;
};

// A closed, outward-wound sphere of 2 * rings * segments triangles around
// the origin, with the unit sphere's normals as smooth shading normals.
TriangleMesh bumpySphere(const BumpySphereShape& shape);

}  // namespace rt
