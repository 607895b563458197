#include <doctest/doctest.h>

#include <random>
#include <set>

#include "bvh/Bvh.hpp"

using namespace rt;

namespace {

std::vector<Aabb> randomBoxes(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> position(-100.0f, 100.0f);
  std::uniform_real_distribution<float> size(0.0f, 3.0f);
  std::vector<Aabb> boxes(count);
  for (Aabb& box : boxes) {
    glm::vec3 p(position(rng), position(rng), position(rng));
    box.grow(p);
    box.grow(p + glm::vec3(size(rng), size(rng), size(rng)));
  }
  return boxes;
}

bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) &&
         glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

// Every primitive in exactly one leaf; every node's box holds its content.
void checkInvariants(const Bvh& bvh, const std::vector<Aabb>& boxes, uint32_t maxDepth) {
  std::multiset<uint32_t> seen;
  for (const BvhNode& node : bvh.nodes) {
    if (node.count == 0) {
      REQUIRE(node.firstIndex + 1 < bvh.nodes.size());
      CHECK(contains(node.bounds, bvh.nodes[node.firstIndex].bounds));
      CHECK(contains(node.bounds, bvh.nodes[node.firstIndex + 1].bounds));
      continue;
    }
    for (uint32_t i = node.firstIndex; i < node.firstIndex + node.count; ++i) {
      uint32_t prim = bvh.primitiveOrder[i];
      seen.insert(prim);
      CHECK(contains(node.bounds, boxes[prim]));
    }
  }
  CHECK(seen.size() == boxes.size());
  CHECK(std::set<uint32_t>(seen.begin(), seen.end()).size() == boxes.size());
  CHECK(bvh.depth <= maxDepth);
}

}  // namespace

TEST_SUITE("bvh") {
  TEST_CASE("an empty input gives an empty tree") {
    Bvh bvh = buildBvh({});
    CHECK(bvh.nodes.empty());
    CHECK(bvh.primitiveOrder.empty());
  }

  TEST_CASE("a single primitive is a leaf root") {
    auto boxes = randomBoxes(1, 1);
    Bvh bvh = buildBvh(boxes);
    REQUIRE(bvh.nodes.size() == 1);
    CHECK(bvh.nodes[0].count == 1);
  }

  TEST_CASE("random boxes: invariants hold and leaves stay small") {
    auto boxes = randomBoxes(5000, 7);
    BvhBuildOptions options;
    Bvh bvh = buildBvh(boxes, options);
    checkInvariants(bvh, boxes, options.maxDepth);
    uint32_t largestLeaf = 0;
    for (const BvhNode& node : bvh.nodes) largestLeaf = std::max(largestLeaf, node.count);
    CHECK(largestLeaf <= options.maxLeafSize);
    // A balanced-ish tree over 5000 boxes is far shallower than the limit.
    CHECK(bvh.depth < 30);
  }

  TEST_CASE("identical boxes still split and respect the depth limit") {
    std::vector<Aabb> boxes(1000);
    for (Aabb& box : boxes) {
      box.grow(glm::vec3(1.0f));
      box.grow(glm::vec3(2.0f));
    }
    BvhBuildOptions options;
    options.maxDepth = 6;
    Bvh bvh = buildBvh(boxes, options);
    checkInvariants(bvh, boxes, options.maxDepth);
  }
}
