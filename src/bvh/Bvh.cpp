#include "bvh/Bvh.hpp"

#include <algorithm>
#include <array>

namespace rt {
namespace {

constexpr float kTraversalCost = 1.0f;  // relative to one primitive test
constexpr uint32_t kMaxBins = 32;

struct BuildTask {
  uint32_t node;
  uint32_t begin;
  uint32_t end;
  uint32_t depth;
};

struct Split {
  int axis = -1;
  float position = 0.0f;  // centroid coordinate: left side is < position
  float cost = std::numeric_limits<float>::max();
};

struct Bin {
  Aabb bounds;
  uint32_t count = 0;
};

class Builder {
 public:
  Builder(const std::vector<Aabb>& boxes, const BvhBuildOptions& options)
      : boxes_(boxes), options_(options) {
    options_.binCount = std::clamp(options_.binCount, 2u, kMaxBins);
  }

  Bvh build() {
    Bvh bvh;
    bvh.primitiveOrder.resize(boxes_.size());
    for (uint32_t i = 0; i < boxes_.size(); ++i) bvh.primitiveOrder[i] = i;
    if (boxes_.empty()) return bvh;
    bvh.nodes.reserve(2 * boxes_.size());
    bvh.nodes.emplace_back();
    std::vector<BuildTask> tasks{{0, 0, static_cast<uint32_t>(boxes_.size()), 0}};
    while (!tasks.empty()) {
      BuildTask task = tasks.back();
      tasks.pop_back();
      bvh.depth = std::max(bvh.depth, task.depth);
      process(bvh, task, tasks);
    }
    return bvh;
  }

 private:
  void process(Bvh& bvh, const BuildTask& task, std::vector<BuildTask>& tasks) {
    auto& order = bvh.primitiveOrder;
    Aabb bounds;
    Aabb centroids;
    for (uint32_t i = task.begin; i < task.end; ++i) {
      bounds.grow(boxes_[order[i]]);
      centroids.grow(boxes_[order[i]].center());
    }
    bvh.nodes[task.node].bounds = bounds;
    uint32_t count = task.end - task.begin;
    if (count <= options_.maxLeafSize || task.depth >= options_.maxDepth) {
      makeLeaf(bvh.nodes[task.node], task);
      return;
    }
    Split split = findSplit(order, task, centroids, bounds);
    uint32_t middle = partition(order, task, split, centroids);
    if (middle == 0) {
      makeLeaf(bvh.nodes[task.node], task);
      return;
    }
    uint32_t left = static_cast<uint32_t>(bvh.nodes.size());
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    bvh.nodes[task.node].firstIndex = left;
    bvh.nodes[task.node].count = 0;
    tasks.push_back({left + 1, middle, task.end, task.depth + 1});
    tasks.push_back({left, task.begin, middle, task.depth + 1});
  }

  static void makeLeaf(BvhNode& node, const BuildTask& task) {
    node.firstIndex = task.begin;
    node.count = task.end - task.begin;
  }

  // Best SAH split over binned centroid positions on all three axes.
  Split findSplit(const std::vector<uint32_t>& order, const BuildTask& task, const Aabb& centroids,
                  const Aabb& bounds) const {
    Split best;
    uint32_t bins = options_.binCount;
    for (int axis = 0; axis < 3; ++axis) {
      float lo = centroids.min[axis];
      float extent = centroids.max[axis] - lo;
      if (!(extent > 0.0f)) continue;
      std::array<Bin, kMaxBins> binned{};
      float scale = static_cast<float>(bins) / extent;
      for (uint32_t i = task.begin; i < task.end; ++i) {
        const Aabb& box = boxes_[order[i]];
        uint32_t b = std::min(bins - 1, static_cast<uint32_t>((box.center()[axis] - lo) * scale));
        binned[b].bounds.grow(box);
        binned[b].count++;
      }
      evaluateBins(binned, bins, axis, lo, extent, bounds.surfaceArea(), best);
    }
    return best;
  }

  static void evaluateBins(const std::array<Bin, kMaxBins>& binned, uint32_t bins, int axis,
                           float lo, float extent, float parentArea, Split& best) {
    std::array<float, kMaxBins> rightCost{};
    Aabb right;
    uint32_t rightCount = 0;
    for (uint32_t b = bins - 1; b > 0; --b) {
      right.grow(binned[b].bounds);
      rightCount += binned[b].count;
      rightCost[b] = right.surfaceArea() * static_cast<float>(rightCount);
    }
    Aabb left;
    uint32_t leftCount = 0;
    for (uint32_t b = 0; b + 1 < bins; ++b) {
      left.grow(binned[b].bounds);
      leftCount += binned[b].count;
      float cost =
          kTraversalCost + (left.surfaceArea() * static_cast<float>(leftCount) + rightCost[b + 1]) /
                               std::max(parentArea, 1e-30f);
      if (cost < best.cost) {
        best = {axis, lo + extent * static_cast<float>(b + 1) / static_cast<float>(bins), cost};
      }
    }
  }

  // Splits [begin, end) at the SAH plane; falls back to a median split when
  // the plane leaves one side empty (e.g. all centroids in one bin). Returns
  // 0 when the range should stay a leaf.
  uint32_t partition(std::vector<uint32_t>& order, const BuildTask& task, const Split& split,
                     const Aabb& centroids) const {
    uint32_t count = task.end - task.begin;
    bool splitWorthIt = split.axis >= 0 && split.cost < static_cast<float>(count);
    if (split.axis >= 0 && (splitWorthIt || count > options_.maxLeafSize * 4)) {
      auto first = order.begin() + task.begin;
      auto last = order.begin() + task.end;
      auto middle = std::partition(
          first, last, [&](uint32_t p) { return boxes_[p].center()[split.axis] < split.position; });
      uint32_t index = static_cast<uint32_t>(middle - order.begin());
      if (index != task.begin && index != task.end) return index;
    }
    if (count <= options_.maxLeafSize * 4 && split.axis >= 0 && !splitWorthIt) return 0;
    return medianSplit(order, task, centroids);
  }

  uint32_t medianSplit(std::vector<uint32_t>& order, const BuildTask& task,
                       const Aabb& centroids) const {
    glm::vec3 extent = centroids.max - centroids.min;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    uint32_t middle = task.begin + (task.end - task.begin) / 2;
    std::nth_element(order.begin() + task.begin, order.begin() + middle, order.begin() + task.end,
                     [&](uint32_t a, uint32_t b) {
                       return boxes_[a].center()[axis] < boxes_[b].center()[axis];
                     });
    return middle;
  }

  const std::vector<Aabb>& boxes_;
  BvhBuildOptions options_;
};

}  // namespace

Bvh buildBvh(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options) {
  return Builder(primitiveBounds, options).build();
}

}  // namespace rt
