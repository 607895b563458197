// A reference point for the traversal table: the textbook GPU walk (Aila and
// Laine's binary layout, full-float boxes of both children in one 64-byte
// node, Moller-Trumbore triangles), primary rays made in the kernel, no
// shading, sampling or accumulation. What lavapipe gives for the plainest
// kernel on the same mesh, camera and BVH build; not the renderer.
#pragma once

#include <glm/glm.hpp>

#include "scene/Scene.hpp"

namespace rt {
class ShaderCompiler;
class VulkanContext;
}  // namespace rt

namespace bench {

struct PlainCamera {
  glm::vec3 position{0.0f};
  float tanHalfFovY = 0.0f;  // looks along -z, y up, square image
};

struct PlainResult {
  double mraysPerSecond = 0;     // best of the repetitions
  double mraysPerCpuSecond = 0;  // best of the repetitions
  double hitFraction = 0;        // primary rays that hit the mesh
};

// `storageBuffers`: nodes and triangles read from storage buffers instead of
// texel buffers. `width` x `width` pixels, `samples` dispatches.
PlainResult measurePlainBvh(rt::VulkanContext& context, const rt::TriangleMesh& mesh,
                            const PlainCamera& camera, bool storageBuffers, uint32_t width,
                            uint32_t samples);

}  // namespace bench
