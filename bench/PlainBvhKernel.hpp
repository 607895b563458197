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

struct PlainLayout {
  bool storageBuffers = false;  // nodes and triangles in storage buffers, not texel buffers
  // Four children per node (the binary tree collapsed by surface area, boxes
  // as structure of arrays), nearest child first; else Aila and Laine's binary.
  bool wide = false;
  // The four-wide nodes with half-float boxes, four texels a node (texel
  // buffers only).
  bool halfWide = false;
  // The binary nodes with half-float boxes in two 16-byte rows, as the
  // renderer lays them out (GpuBvhNode); texel buffers, or storage buffers
  // with storageBuffers.
  bool halfBinary = false;
  // Nodes and triangles read through buffer device addresses (binary only).
  bool deviceAddress = false;
  // The stack as the renderer keeps it: the top in registers, the array
  // written only when some lane spills (a subgroup vote).
  bool registerStack = false;
};

// `width` x `width` pixels, `samples` dispatches.
PlainResult measurePlainBvh(rt::VulkanContext& context, const rt::TriangleMesh& mesh,
                            const PlainCamera& camera, const PlainLayout& layout, uint32_t width,
                            uint32_t samples);

}  // namespace bench
