// Lays binary BVHs (src/bvh) out as the GPU's nodes (GpuBvhNode: both
// children's boxes in the parent, leaves packed into child references).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "bvh/Bvh.hpp"
#include "gpu_types.h"

namespace rt {

// Child reference of the leaf over bvh.primitiveOrder[first, first + count).
using LeafReference = std::function<uint32_t(uint32_t first, uint32_t count)>;

// Appends `bvh` to `nodes` and returns the index of its root. A tree that is
// a single leaf gets a root whose second child is empty.
uint32_t appendBvhNodes(const Bvh& bvh, const LeafReference& leafReference,
                        std::vector<gpu::GpuBvhNode>& nodes);

// A tree that prunes nothing: `count` items in index order under leaves of
// at most `leafSize`, every box `bounds`. Traversing it tests every item
// (brute force through the same kernel, to compare against).
Bvh bruteForceTree(uint32_t count, uint32_t leafSize, const Aabb& bounds);

// Half-float bits of v rounded down (or up): a box stored this way still
// holds everything the float box held.
uint16_t halfTowards(float v, bool up);

// Leaf references of the two levels (see GpuBvhNode in gpu_types.h).
uint32_t topLevelLeaf(uint32_t item, uint32_t kind);
uint32_t meshLeaf(uint32_t firstTriangle, uint32_t count);

}  // namespace rt
