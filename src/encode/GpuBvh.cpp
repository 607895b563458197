#include "encode/GpuBvh.hpp"

#include <fmt/format.h>

#include <glm/gtc/packing.hpp>

#include "util/Error.hpp"

namespace rt {

uint16_t halfTowards(float v, bool up) {
  uint16_t h = static_cast<uint16_t>(glm::packHalf1x16(v));
  float back = glm::unpackHalf1x16(h);
  bool negative = (h & 0x8000u) != 0;
  if (up && back < v) {
    if (h == 0x8000u) return 0x0001u;  // -0 -> smallest positive
    return static_cast<uint16_t>(negative ? h - 1 : h + 1);
  }
  if (!up && back > v) {
    if (h == 0x0000u) return 0x8001u;  // +0 -> smallest negative
    return static_cast<uint16_t>(negative ? h + 1 : h - 1);
  }
  return h;
}

namespace {

uint32_t halfPair(float low, bool lowUp, float high, bool highUp) {
  return uint32_t(halfTowards(low, lowUp)) | uint32_t(halfTowards(high, highUp)) << 16;
}

void setChild(gpu::GpuBvhNode& node, bool right, const Aabb& box, uint32_t reference) {
  const glm::vec3& lo = box.min;
  const glm::vec3& hi = box.max;
  uint32_t minXY = halfPair(lo.x, false, lo.y, false);
  uint32_t minZMaxX = halfPair(lo.z, false, hi.x, true);
  uint32_t maxYZ = halfPair(hi.y, true, hi.z, true);
  if (right) {
    node.rightRef = reference;
    node.rightMinXY = minXY;
    node.rightMinZMaxX = minZMaxX;
    node.rightMaxYZ = maxYZ;
  } else {
    node.leftRef = reference;
    node.leftMinXY = minXY;
    node.leftMinZMaxX = minZMaxX;
    node.leftMaxYZ = maxYZ;
  }
}

uint32_t leafField(uint32_t first, uint32_t field) {
  if (field > RT_REF_MAX_LEAF_SIZE || first > RT_REF_FIRST_MASK) {
    throw Error(
        fmt::format("scene too large: BVH leaf at item {} does not fit a node reference", first));
  }
  return RT_REF_LEAF | field << RT_REF_COUNT_SHIFT | first;
}

}  // namespace

// Top-level kinds are stored plus one: field 0 is the empty leaf at both levels.
uint32_t topLevelLeaf(uint32_t item, uint32_t kind) { return leafField(item, kind + 1); }

uint32_t meshLeaf(uint32_t firstTriangle, uint32_t count) {
  return RT_REF_MESH | leafField(firstTriangle, count);
}

uint32_t appendBvhNodes(const Bvh& bvh, const LeafReference& leafReference,
                        std::vector<gpu::GpuBvhNode>& nodes) {
  const uint32_t root = static_cast<uint32_t>(nodes.size());
  const uint32_t empty = RT_REF_LEAF;
  if (bvh.nodes.empty() || bvh.nodes[0].count > 0) {
    gpu::GpuBvhNode single{};
    if (!bvh.nodes.empty()) {
      const BvhNode& top = bvh.nodes[0];
      setChild(single, false, top.bounds, leafReference(top.firstIndex, top.count));
    } else {
      setChild(single, false, Aabb{}, empty);
    }
    setChild(single, true, Aabb{}, empty);
    nodes.push_back(single);
    return root;
  }
  // Depth first, left child right after its parent (locality for the
  // near-first walk). Each work item: (binary interior node, GPU slot).
  std::vector<std::pair<uint32_t, uint32_t>> work{{0u, root}};
  nodes.emplace_back();
  while (!work.empty()) {
    auto [binary, slot] = work.back();
    work.pop_back();
    uint32_t firstChild = bvh.nodes[binary].firstIndex;
    uint32_t refs[2];
    for (uint32_t side = 0; side < 2; ++side) {
      const BvhNode& child = bvh.nodes[firstChild + side];
      if (child.count > 0) {
        refs[side] = leafReference(child.firstIndex, child.count);
      } else {
        refs[side] = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
      }
    }
    // Right first on the work stack, so the left subtree is laid out first.
    for (int side = 1; side >= 0; --side) {
      const BvhNode& child = bvh.nodes[firstChild + static_cast<uint32_t>(side)];
      setChild(nodes[slot], side == 1, child.bounds, refs[side]);
      if (child.count == 0) work.push_back({firstChild + static_cast<uint32_t>(side), refs[side]});
    }
  }
  return root;
}

Bvh bruteForceTree(uint32_t count, uint32_t leafSize, const Aabb& bounds) {
  Bvh tree;
  tree.primitiveOrder.resize(count);
  for (uint32_t i = 0; i < count; ++i) tree.primitiveOrder[i] = i;
  if (count == 0) return tree;
  struct Range {
    uint32_t node, begin, end, depth;
  };
  tree.nodes.emplace_back();
  std::vector<Range> work{{0, 0, count, 0}};
  while (!work.empty()) {
    Range range = work.back();
    work.pop_back();
    tree.depth = std::max(tree.depth, range.depth);
    BvhNode node{bounds, range.begin, range.end - range.begin};
    if (node.count > leafSize) {
      node.firstIndex = static_cast<uint32_t>(tree.nodes.size());
      node.count = 0;
      uint32_t middle = range.begin + (range.end - range.begin) / 2;
      tree.nodes.emplace_back();
      tree.nodes.emplace_back();
      work.push_back({node.firstIndex + 1, middle, range.end, range.depth + 1});
      work.push_back({node.firstIndex, range.begin, middle, range.depth + 1});
    }
    tree.nodes[range.node] = node;
  }
  return tree;
}

}  // namespace rt
