// Area lights flattened for the GPU: the pieces of each light's surface
// with the shares of its area by which they are sampled, and the radiance
// the light's intensity gives its surface.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "encode/GpuFrame.hpp"
#include "gpu_types.h"
#include "scene/Scene.hpp"

namespace rt {

struct FlatAreaLights {
  std::vector<gpu::GpuAreaLight> lights;  // in Scene::areaLights order
  std::vector<gpu::GpuEmitter> emitters;
  std::vector<glm::vec3> emission;  // of each light's surface (GpuMaterial::emission)
};

// `frame` places the surfaces in GPU coordinates; `lightScale` is the
// scene's (LightingConventions), which emission includes.
FlatAreaLights flattenAreaLights(const Scene& scene, const GpuFrame& frame, float lightScale);

}  // namespace rt
