#include "PlainBvhKernel.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "bvh/Bvh.hpp"
#include "encode/GpuBvh.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Clock.hpp"

namespace bench {
namespace {

constexpr uint32_t kLeafBit = 0x80000000u;
constexpr uint32_t kCountBits = 3;  // leaf: kLeafBit | first << 3 | count (count <= 7)

struct PlainParams {
  glm::vec4 position;
  float tanHalfFovY;
  uint32_t width;
  uint32_t sample;
  uint32_t pad;
  VkDeviceAddress nodeAddress;
  VkDeviceAddress triangleAddress;
};

float bitsFloat(uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// Interior nodes of the binary tree: the nodes of the binary layouts.
size_t interiorNodeCount(const rt::Bvh& bvh) {
  return size_t(std::count_if(bvh.nodes.begin(), bvh.nodes.end(),
                              [](const rt::BvhNode& n) { return n.count == 0; }));
}

// Each binary node's reference as a child in the binary layouts: its index
// among the interior nodes (which they store in order), or for a leaf
// kLeafBit | first << kCountBits | count.
std::vector<uint32_t> childReferences(const rt::Bvh& bvh) {
  std::vector<uint32_t> references(bvh.nodes.size());
  uint32_t interior = 0;
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const rt::BvhNode& node = bvh.nodes[i];
    references[i] =
        node.count == 0 ? interior++ : kLeafBit | node.firstIndex << kCountBits | node.count;
  }
  return references;
}

// Nodes: (a.lo.x, a.hi.x, a.lo.y, a.hi.y), (b.lo.x, b.hi.x, b.lo.y, b.hi.y),
// (a.lo.z, a.hi.z, b.lo.z, b.hi.z), (child a, child b, 0, 0): interior nodes only.
std::vector<float> layoutNodes(const rt::Bvh& bvh) {
  const std::vector<uint32_t> reference = childReferences(bvh);
  const size_t interiorCount = interiorNodeCount(bvh);
  std::vector<float> nodes;
  nodes.reserve(interiorCount * 16);
  for (const rt::BvhNode& node : bvh.nodes) {
    if (node.count != 0) continue;
    const rt::Aabb& a = bvh.nodes[node.firstIndex].bounds;
    const rt::Aabb& b = bvh.nodes[node.firstIndex + 1].bounds;
    float row[16] = {a.min.x,
                     a.max.x,
                     a.min.y,
                     a.max.y,
                     b.min.x,
                     b.max.x,
                     b.min.y,
                     b.max.y,
                     a.min.z,
                     a.max.z,
                     b.min.z,
                     b.max.z,
                     bitsFloat(reference[node.firstIndex]),
                     bitsFloat(reference[node.firstIndex + 1]),
                     0.0f,
                     0.0f};
    nodes.insert(nodes.end(), row, row + 16);
  }
  return nodes;
}

// The binary tree collapsed into nodes of up to four children: a node takes
// its binary children and opens the largest interior one until it has four
// (greedy by surface area). Rows: min x, max x, min y, max y, min z, max z of
// the four boxes, then the references (unused slots: empty boxes, DONE).
std::vector<float> layoutWideNodes(const rt::Bvh& bvh) {
  auto isLeaf = [&](uint32_t n) { return bvh.nodes[n].count != 0; };
  auto childrenOf = [&](uint32_t binary) {
    std::vector<uint32_t> children{bvh.nodes[binary].firstIndex, bvh.nodes[binary].firstIndex + 1};
    while (children.size() < 4) {
      int open = -1;
      float largest = -1.0f;
      for (size_t i = 0; i < children.size(); ++i) {
        if (isLeaf(children[i])) continue;
        float area = bvh.nodes[children[i]].bounds.surfaceArea();
        if (area > largest) largest = area, open = int(i);
      }
      if (open < 0) break;
      uint32_t opened = children[size_t(open)];
      children.erase(children.begin() + open);
      children.push_back(bvh.nodes[opened].firstIndex);
      children.push_back(bvh.nodes[opened].firstIndex + 1);
    }
    return children;
  };
  std::vector<uint32_t> order{0};  // binary nodes that become wide nodes, breadth first
  std::vector<std::vector<uint32_t>> children;
  std::vector<uint32_t> wideIndex(bvh.nodes.size(), 0);
  for (size_t i = 0; i < order.size(); ++i) {
    children.push_back(childrenOf(order[i]));
    for (uint32_t c : children.back()) {
      if (!isLeaf(c)) {
        wideIndex[c] = static_cast<uint32_t>(order.size());
        order.push_back(c);
      }
    }
  }
  std::vector<float> nodes;
  for (const std::vector<uint32_t>& kids : children) {
    float rows[7][4];
    for (int slot = 0; slot < 4; ++slot) {
      bool used = size_t(slot) < kids.size();
      const rt::BvhNode* child = used ? &bvh.nodes[kids[size_t(slot)]] : nullptr;
      for (int axis = 0; axis < 3; ++axis) {
        rows[2 * axis][slot] = used ? child->bounds.min[axis] : 1e30f;
        rows[2 * axis + 1][slot] = used ? child->bounds.max[axis] : -1e30f;
      }
      uint32_t ref = !used ? 0xffffffffu
                     : child->count == 0
                         ? wideIndex[kids[size_t(slot)]]
                         : kLeafBit | child->firstIndex << kCountBits | child->count;
      rows[6][slot] = bitsFloat(ref);
    }
    nodes.insert(nodes.end(), &rows[0][0], &rows[0][0] + 28);
  }
  return nodes;
}

// The wide nodes' boxes as half floats: rows x, y, z (min of c0 c1, min of
// c2 c3, max of c0 c1, max of c2 c3), then the references.
std::vector<uint32_t> layoutHalfWide(const std::vector<float>& wide) {
  std::vector<uint32_t> out;
  for (size_t n = 0; n + 28 <= wide.size(); n += 28) {
    const float* rows = &wide[n];
    for (int axis = 0; axis < 3; ++axis) {
      const float* lo = rows + 8 * axis;
      const float* hi = lo + 4;
      auto pair = [&](const float* v, int a, bool up) {
        return uint32_t(rt::halfTowards(v[a], up)) | uint32_t(rt::halfTowards(v[a + 1], up)) << 16;
      };
      out.push_back(pair(lo, 0, false));
      out.push_back(pair(lo, 2, false));
      out.push_back(pair(hi, 0, true));
      out.push_back(pair(hi, 2, true));
    }
    for (int c = 0; c < 4; ++c) {
      uint32_t ref;
      std::memcpy(&ref, &rows[24 + c], 4);
      out.push_back(ref);
    }
  }
  return out;
}

// The binary nodes with half-float boxes rounded outwards, two texels a node:
// (ref a, ref b, a.min xy, a.min z a.max x), (a.max yz, b.min xy, b.min z
// b.max x, b.max yz), as in the renderer's GpuBvhNode.
std::vector<uint32_t> layoutHalfBinary(const rt::Bvh& bvh) {
  const std::vector<uint32_t> reference = childReferences(bvh);
  const size_t interiorCount = interiorNodeCount(bvh);
  auto pair = [](float low, bool lowUp, float high, bool highUp) {
    return uint32_t(rt::halfTowards(low, lowUp)) | uint32_t(rt::halfTowards(high, highUp)) << 16;
  };
  std::vector<uint32_t> out;
  out.reserve(interiorCount * 8);
  for (const rt::BvhNode& node : bvh.nodes) {
    if (node.count != 0) continue;
    const rt::Aabb& a = bvh.nodes[node.firstIndex].bounds;
    const rt::Aabb& b = bvh.nodes[node.firstIndex + 1].bounds;
    uint32_t words[8] = {reference[node.firstIndex],           reference[node.firstIndex + 1],
                         pair(a.min.x, false, a.min.y, false), pair(a.min.z, false, a.max.x, true),
                         pair(a.max.y, true, a.max.z, true),   pair(b.min.x, false, b.min.y, false),
                         pair(b.min.z, false, b.max.x, true),  pair(b.max.y, true, b.max.z, true)};
    out.insert(out.end(), words, words + 8);
  }
  return out;
}

// Triangles in leaf order as (v0, v1 - v0, v2 - v0), one vec4 each.
std::vector<float> layoutTriangles(const rt::TriangleMesh& mesh, const rt::Bvh& bvh) {
  std::vector<float> triangles;
  triangles.reserve(bvh.primitiveOrder.size() * 12);
  for (uint32_t face : bvh.primitiveOrder) {
    glm::uvec3 f = mesh.faces[face];
    glm::vec3 v0 = mesh.positions[f.x];
    glm::vec3 e1 = mesh.positions[f.y] - v0, e2 = mesh.positions[f.z] - v0;
    float row[12] = {v0.x, v0.y, v0.z, 0.0f, e1.x, e1.y, e1.z, 0.0f, e2.x, e2.y, e2.z, 0.0f};
    triangles.insert(triangles.end(), row, row + 12);
  }
  return triangles;
}

rt::Bvh buildMeshBvh(const rt::TriangleMesh& mesh) {
  rt::BvhBuildOptions options;  // the renderer's leaves and node cost
  options.maxLeafSize = std::min(options.maxLeafSize, (1u << kCountBits) - 1);
  return rt::buildBvh(rt::triangleBounds(mesh.positions, mesh.faces), options);
}

}  // namespace

PlainResult measurePlainBvh(rt::VulkanContext& context, const rt::TriangleMesh& mesh,
                            const PlainCamera& camera, const PlainLayout& layout, uint32_t width,
                            uint32_t samples) {
  const bool halfNodeTexels = layout.halfWide || (layout.halfBinary && !layout.storageBuffers);
  const bool storageBuffers = layout.storageBuffers && !halfNodeTexels;
  rt::Bvh bvh = buildMeshBvh(mesh);
  const bool wide = layout.wide || layout.halfWide;
  std::vector<float> nodes = wide ? layoutWideNodes(bvh) : layoutNodes(bvh);
  std::vector<uint32_t> halfNodes = layout.halfWide     ? layoutHalfWide(nodes)
                                    : layout.halfBinary ? layoutHalfBinary(bvh)
                                                        : std::vector<uint32_t>{};
  std::vector<float> triangles = layoutTriangles(mesh, bvh);
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
      (layout.deviceAddress ? VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT : 0);
  // Every node layout is 32-bit words.
  const bool halfWords = layout.halfWide || layout.halfBinary;
  const void* nodeWords = halfWords ? static_cast<const void*>(halfNodes.data()) : nodes.data();
  size_t nodeBytes = (halfWords ? halfNodes.size() : nodes.size()) * sizeof(float);
  rt::Buffer nodeBuffer(context, nodeBytes, usage);
  rt::Buffer triangleBuffer(context, triangles.size() * sizeof(float), usage);
  rt::Buffer distances(context, size_t(width) * width * sizeof(float),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  nodeBuffer.upload(nodeWords, nodeBytes);
  triangleBuffer.upload(triangles.data(), triangles.size() * sizeof(float));

  rt::ShaderCompiler compiler(RT_BENCH_SHADER_DIR, "");
  rt::ShaderDefines defines;
  if (storageBuffers) defines.emplace_back("PLAIN_STORAGE_BUFFERS", "1");
  if (layout.deviceAddress) defines.emplace_back("PLAIN_DEVICE_ADDRESS", "1");
  if (wide) defines.emplace_back("PLAIN_WIDE", "1");
  if (layout.halfWide) defines.emplace_back("PLAIN_WIDE_HALF", "1");
  if (layout.halfBinary) defines.emplace_back("PLAIN_BINARY_HALF", "1");
  if (layout.registerStack) defines.emplace_back("PLAIN_REGISTER_STACK", "1");
  defines.emplace_back("PLAIN_NODE_TEXELS", layout.wide ? "7u" : "4u");
  VkDescriptorType sceneType =
      storageBuffers ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  rt::ComputeKernel kernel(context, compiler.compile("plain_bvh.comp", defines),
                           {{0, sceneType}, {1, sceneType}, {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                           sizeof(PlainParams));
  if (storageBuffers) {
    kernel.bind(0, nodeBuffer);
    kernel.bind(1, triangleBuffer);
  } else {
    kernel.bindTexels(0, nodeBuffer,
                      halfNodeTexels ? VK_FORMAT_R32G32B32A32_UINT : VK_FORMAT_R32G32B32A32_SFLOAT);
    kernel.bindTexels(1, triangleBuffer, VK_FORMAT_R32G32B32A32_SFLOAT);
  }
  kernel.bind(2, distances);

  PlainParams params{glm::vec4(camera.position, 0.0f), camera.tanHalfFovY, width, 0, 0, 0, 0};
  if (layout.deviceAddress) {
    params.nodeAddress = nodeBuffer.deviceAddress();
    params.triangleAddress = triangleBuffer.deviceAddress();
  }
  PlainResult result;
  const double rays = double(width) * width * samples;
  for (int repetition = 0; repetition < 4; ++repetition) {  // the first one warms up
    auto start = rt::SteadyClock::now();
    double cpuStart = rt::processCpuSeconds();
    context.submitAndWait([&](VkCommandBuffer commands) {
      for (params.sample = 0; params.sample < samples; ++params.sample) {
        kernel.recordDispatch(commands, &params, (width + 7) / 8, (width + 7) / 8);
      }
    });
    double wall = rt::secondsSince(start), cpu = rt::processCpuSeconds() - cpuStart;
    if (repetition == 0) continue;
    result.mraysPerSecond = std::max(result.mraysPerSecond, rays / wall * 1e-6);
    result.mraysPerCpuSecond = std::max(result.mraysPerCpuSecond, rays / cpu * 1e-6);
  }
  std::vector<float> t(size_t(width) * width);
  distances.download(t.data(), t.size() * sizeof(float));
  result.hitFraction =
      double(std::count_if(t.begin(), t.end(), [](float d) { return d > 0; })) / double(t.size());
  return result;
}

}  // namespace bench
