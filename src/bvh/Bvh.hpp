// Bounding volume hierarchy over axis-aligned boxes, built on the CPU with
// the binned surface area heuristic, on several threads. Knows nothing about
// primitive kinds: callers give one box per primitive and reorder their
// primitives by `primitiveOrder`. The tree is the same whatever the thread
// count (splits are exact functions of the boxes; subtrees built apart are
// laid out as one thread lays them out).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

namespace rt {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};

  void grow(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void grow(const Aabb& box) {
    min = glm::min(min, box.min);
    max = glm::max(max, box.max);
  }
  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  float surfaceArea() const {
    if (empty()) return 0.0f;
    glm::vec3 d = max - min;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
};

// count == 0: interior node, children at firstIndex and firstIndex + 1.
// count > 0: leaf over primitiveOrder[firstIndex, firstIndex + count).
struct BvhNode {
  Aabb bounds;
  uint32_t firstIndex = 0;
  uint32_t count = 0;
};

struct Bvh {
  std::vector<BvhNode> nodes;            // nodes[0] is the root
  std::vector<uint32_t> primitiveOrder;  // leaf slot -> caller's primitive index
  uint32_t depth = 0;                    // levels below the root
};

struct BvhBuildOptions {
  // Ranges up to this size become leaves when the SAH says a leaf is cheaper;
  // larger ones are always split (except at maxDepth).
  uint32_t maxLeafSize = 4;
  uint32_t maxDepth = 48;  // must not exceed RT_BVH_MAX_DEPTH (traversal stack)
  uint32_t binCount = 16;
  // SAH cost of visiting a node, relative to one primitive test. The GPU
  // traversal visits a node and tests a leaf item in the same loop
  // iteration, so nodes are dear: 4 gives leaves of about 3 triangles (1
  // gave about 1), a BVH with a third of the nodes that builds about 1.5x
  // faster and renders as fast (bench/README.md).
  float traversalCost = 4.0f;
  uint32_t threads = 0;  // 0: one per hardware thread
};

Bvh buildBvh(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options = {});

// One box per triangle (corner indices into `positions`), for buildBvh.
std::vector<Aabb> triangleBounds(const std::vector<glm::vec3>& positions,
                                 const std::vector<glm::uvec3>& faces);

}  // namespace rt
