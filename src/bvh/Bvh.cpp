#include "bvh/Bvh.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <thread>

namespace rt {
namespace {

constexpr float kTraversalCost = 1.0f;  // relative to one primitive test
constexpr uint32_t kMaxBins = 32;
// Ranges at least this large are split with several threads binning them,
// and their two halves may be built on two threads.
constexpr uint32_t kParallelBinning = 1u << 17;
constexpr uint32_t kParallelSubtree = 1u << 12;

// A primitive's box with its caller index: partitioned in place, so the
// build streams through one array instead of gathering boxes by index.
struct PrimRef {
  Aabb box;
  uint32_t index;
};

glm::vec3 centroid(const PrimRef& ref) { return ref.box.min + ref.box.max; }  // x2, cheaper

struct RangeBounds {
  Aabb boxes;
  Aabb centroids;  // of centroid(), i.e. doubled
  void grow(const RangeBounds& other) {
    boxes.grow(other.boxes);
    centroids.grow(other.centroids);
  }
};

struct Bin {
  Aabb bounds;
  uint32_t count = 0;
};

using AxisBins = std::array<std::array<Bin, kMaxBins>, 3>;

struct Split {
  int axis = -1;
  uint32_t bin = 0;  // first bin of the right side
  float cost = std::numeric_limits<float>::max();
};

// Maps a centroid coordinate to its bin along one axis.
struct BinMapping {
  glm::vec3 origin;
  glm::vec3 scale;
  uint32_t bins;
  uint32_t operator()(const PrimRef& ref, int axis) const {
    float position = (centroid(ref)[axis] - origin[axis]) * scale[axis];
    return std::min(bins - 1, static_cast<uint32_t>(std::max(position, 0.0f)));
  }
};

// Runs body(begin, end) over [begin, end) cut into `parts` consecutive chunks,
// the first on this thread; results go to per-chunk slots, so merging them in
// chunk order keeps the outcome independent of timing.
template <typename Body>
void forChunks(uint32_t begin, uint32_t end, uint32_t parts, const Body& body) {
  std::vector<std::thread> workers;
  uint32_t size = (end - begin + parts - 1) / parts;
  for (uint32_t part = 1; part < parts; ++part) {
    uint32_t from = std::min(end, begin + part * size);
    uint32_t to = std::min(end, from + size);
    workers.emplace_back([&body, part, from, to] { body(part, from, to); });
  }
  body(0u, begin, std::min(end, begin + size));
  for (std::thread& worker : workers) worker.join();
}

// Nodes of one subtree in the builder's layout (root first; each interior
// node's children are a pair, followed by the left then the right subtree's
// descendants), so subtrees built apart concatenate into the same tree a
// single thread builds.
struct Subtree {
  std::vector<BvhNode> nodes;
  uint32_t depth = 0;
};

class Builder {
 public:
  Builder(const std::vector<Aabb>& boxes, const BvhBuildOptions& options) : options_(options) {
    options_.binCount = std::clamp(options_.binCount, 2u, kMaxBins);
    options_.maxLeafSize = std::max(options_.maxLeafSize, 1u);
    uint32_t threads = options_.threads ? options_.threads : std::thread::hardware_concurrency();
    threads_ = std::max(threads, 1u);
    spareThreads_ = static_cast<int>(threads_) - 1;
    refs_.resize(boxes.size());
    forChunks(0, static_cast<uint32_t>(boxes.size()), chunksFor(uint32_t(boxes.size())),
              [&](uint32_t, uint32_t from, uint32_t to) {
                for (uint32_t i = from; i < to; ++i) refs_[i] = {boxes[i], i};
              });
  }

  Bvh build() {
    Bvh bvh;
    if (!refs_.empty()) {
      Subtree tree = buildRange(0, static_cast<uint32_t>(refs_.size()), 0);
      bvh.nodes = std::move(tree.nodes);
      bvh.depth = tree.depth;
    }
    bvh.primitiveOrder.resize(refs_.size());
    for (size_t i = 0; i < refs_.size(); ++i) bvh.primitiveOrder[i] = refs_[i].index;
    return bvh;
  }

 private:
  uint32_t chunksFor(uint32_t count) const { return count >= kParallelBinning ? threads_ : 1u; }

  // Splits a large range, building its halves on two threads when one is
  // free, then stitches them under a root. Small ranges go sequential.
  Subtree buildRange(uint32_t begin, uint32_t end, uint32_t depth) {
    if (end - begin < kParallelSubtree) return buildSequential(begin, end, depth);
    BvhNode root;
    uint32_t middle = splitRange(begin, end, depth, root);
    if (middle == end) return {{root}, depth};
    Subtree left;
    std::thread worker;
    if (spareThreads_.fetch_sub(1) > 0) {
      worker = std::thread([&] { left = buildRange(begin, middle, depth + 1); });
    } else {
      spareThreads_.fetch_add(1);
      left = buildRange(begin, middle, depth + 1);
    }
    Subtree right = buildRange(middle, end, depth + 1);
    if (worker.joinable()) {
      worker.join();
      spareThreads_.fetch_add(1);
    }
    return stitch(root, std::move(left), std::move(right));
  }

  static Subtree stitch(BvhNode root, Subtree left, Subtree right) {
    Subtree out;
    out.depth = std::max(left.depth, right.depth);
    out.nodes.reserve(1 + left.nodes.size() + right.nodes.size());
    root.firstIndex = 1;
    root.count = 0;
    out.nodes.push_back(root);
    // Children's own descendants move from index 1 of their subtree to
    // `offset` here.
    auto moved = [](BvhNode node, uint32_t offset) {
      if (node.count == 0) node.firstIndex += offset - 1;
      return node;
    };
    uint32_t leftOffset = 3;
    uint32_t rightOffset = leftOffset + static_cast<uint32_t>(left.nodes.size()) - 1;
    out.nodes.push_back(moved(left.nodes[0], leftOffset));
    out.nodes.push_back(moved(right.nodes[0], rightOffset));
    for (size_t i = 1; i < left.nodes.size(); ++i)
      out.nodes.push_back(moved(left.nodes[i], leftOffset));
    for (size_t i = 1; i < right.nodes.size(); ++i) {
      out.nodes.push_back(moved(right.nodes[i], rightOffset));
    }
    return out;
  }

  Subtree buildSequential(uint32_t begin, uint32_t end, uint32_t depth) {
    struct Task {
      uint32_t node, begin, end, depth;
    };
    Subtree out;
    out.nodes.reserve(2 * (end - begin) / options_.maxLeafSize + 1);
    out.nodes.emplace_back();
    std::vector<Task> tasks{{0, begin, end, depth}};
    while (!tasks.empty()) {
      Task task = tasks.back();
      tasks.pop_back();
      out.depth = std::max(out.depth, task.depth);
      BvhNode node;
      uint32_t middle = splitRange(task.begin, task.end, task.depth, node);
      if (middle != task.end) {
        node.firstIndex = static_cast<uint32_t>(out.nodes.size());
        node.count = 0;
        out.nodes.emplace_back();
        out.nodes.emplace_back();
        tasks.push_back({node.firstIndex + 1, middle, task.end, task.depth + 1});
        tasks.push_back({node.firstIndex, task.begin, middle, task.depth + 1});
      }
      out.nodes[task.node] = node;
    }
    return out;
  }

  // Fills `node` with the range's bounds; either makes it a leaf (returns
  // end) or partitions the range and returns where the right half starts.
  uint32_t splitRange(uint32_t begin, uint32_t end, uint32_t depth, BvhNode& node) {
    uint32_t count = end - begin;
    RangeBounds bounds = rangeBounds(begin, end);
    node.bounds = bounds.boxes;
    node.firstIndex = begin;
    node.count = count;
    if (count == 1 || depth >= options_.maxDepth) return end;
    Split split = findSplit(begin, end, bounds);
    bool leafIsCheaper = split.axis < 0 || split.cost >= static_cast<float>(count);
    if (count <= options_.maxLeafSize && leafIsCheaper) return end;
    if (split.axis < 0) return begin + count / 2;  // all centroids equal: any halving will do
    BinMapping mapping = mappingFor(bounds);
    auto first = refs_.begin() + begin;
    auto middle = std::partition(first, refs_.begin() + end, [&](const PrimRef& ref) {
      return mapping(ref, split.axis) < split.bin;
    });
    return static_cast<uint32_t>(middle - refs_.begin());
  }

  RangeBounds rangeBounds(uint32_t begin, uint32_t end) const {
    uint32_t parts = chunksFor(end - begin);
    std::vector<RangeBounds> partial(parts);
    forChunks(begin, end, parts, [&](uint32_t part, uint32_t from, uint32_t to) {
      RangeBounds local;
      for (uint32_t i = from; i < to; ++i) {
        local.boxes.grow(refs_[i].box);
        local.centroids.grow(centroid(refs_[i]));
      }
      partial[part] = local;
    });
    RangeBounds total;
    for (const RangeBounds& part : partial) total.grow(part);
    return total;
  }

  BinMapping mappingFor(const RangeBounds& bounds) const {
    glm::vec3 extent = bounds.centroids.max - bounds.centroids.min;
    glm::vec3 scale(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
      if (extent[axis] > 0.0f) scale[axis] = static_cast<float>(options_.binCount) / extent[axis];
    }
    return {bounds.centroids.min, scale, options_.binCount};
  }

  // Best SAH split over binned centroid positions on all three axes, all
  // binned in one pass over the range.
  Split findSplit(uint32_t begin, uint32_t end, const RangeBounds& bounds) const {
    BinMapping mapping = mappingFor(bounds);
    uint32_t parts = chunksFor(end - begin);
    std::vector<AxisBins> partial(parts);
    forChunks(begin, end, parts, [&](uint32_t part, uint32_t from, uint32_t to) {
      AxisBins local{};
      for (uint32_t i = from; i < to; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
          Bin& bin = local[axis][mapping(refs_[i], axis)];
          bin.bounds.grow(refs_[i].box);
          bin.count++;
        }
      }
      partial[part] = local;
    });
    AxisBins bins = partial[0];
    for (uint32_t part = 1; part < parts; ++part) {
      for (int axis = 0; axis < 3; ++axis) {
        for (uint32_t b = 0; b < options_.binCount; ++b) {
          bins[axis][b].bounds.grow(partial[part][axis][b].bounds);
          bins[axis][b].count += partial[part][axis][b].count;
        }
      }
    }
    Split best;
    float parentArea = std::max(bounds.boxes.surfaceArea(), 1e-30f);
    for (int axis = 0; axis < 3; ++axis) {
      if (mapping.scale[axis] > 0.0f) evaluateBins(bins[axis], axis, parentArea, best);
    }
    return best;
  }

  void evaluateBins(const std::array<Bin, kMaxBins>& binned, int axis, float parentArea,
                    Split& best) const {
    uint32_t bins = options_.binCount;
    std::array<float, kMaxBins> rightCost{};
    std::array<uint32_t, kMaxBins> rightCount{};
    Aabb right;
    uint32_t rightTotal = 0;
    for (uint32_t b = bins - 1; b > 0; --b) {
      right.grow(binned[b].bounds);
      rightTotal += binned[b].count;
      rightCost[b] = right.surfaceArea() * static_cast<float>(rightTotal);
      rightCount[b] = rightTotal;
    }
    Aabb left;
    uint32_t leftCount = 0;
    for (uint32_t b = 0; b + 1 < bins; ++b) {
      left.grow(binned[b].bounds);
      leftCount += binned[b].count;
      if (leftCount == 0 || rightCount[b + 1] == 0) continue;
      float cost =
          kTraversalCost +
          (left.surfaceArea() * static_cast<float>(leftCount) + rightCost[b + 1]) / parentArea;
      if (cost < best.cost) best = {axis, b + 1, cost};
    }
  }

  std::vector<PrimRef> refs_;
  BvhBuildOptions options_;
  uint32_t threads_ = 1;
  std::atomic<int> spareThreads_{0};
};

}  // namespace

Bvh buildBvh(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options) {
  return Builder(primitiveBounds, options).build();
}

}  // namespace rt
