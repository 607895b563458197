#include "bvh/Bvh.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <thread>

#include "util/Arithmetic.hpp"

namespace rt {
namespace {

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

// Four floats in one vector register (GCC/Clang vector extension): the
// binning loop grows a box with two vector min/max instead of six scalar ones.
using Float4 = float __attribute__((vector_size(16)));

Float4 load4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }
Float4 max4(Float4 a, Float4 b) { return a > b ? a : b; }

// Child centroid bounds come from the partition pass, so bins hold boxes
// only, in lanes x, y, z (w unused).
struct Bin {
  Float4 min = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                std::numeric_limits<float>::max(), 0.0f};
  Float4 max = {-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                -std::numeric_limits<float>::max(), 0.0f};
  uint32_t count = 0;

  Aabb bounds() const { return {{min[0], min[1], min[2]}, {max[0], max[1], max[2]}}; }
};

using AxisBins = std::array<std::array<Bin, kMaxBins>, 3>;

struct Split {
  int axis = -1;
  uint32_t bin = 0;  // first bin of the right side
  float cost = std::numeric_limits<float>::max();
  RangeBounds left;  // of the two sides: boxes from the bins, centroids from the partition
  RangeBounds right;
};

// Maps a centroid to its bin along each axis.
struct BinMapping {
  glm::vec3 origin;
  glm::vec3 scale;
  uint32_t bins;
  uint32_t operator()(const glm::vec3& doubledCentroid, int axis) const {
    float position = (doubledCentroid[axis] - origin[axis]) * scale[axis];
    return std::min(bins - 1, static_cast<uint32_t>(std::max(position, 0.0f)));
  }
};

// Runs body(begin, end) over [begin, end) cut into `parts` consecutive chunks,
// the first on this thread; results go to per-chunk slots, so merging them in
// chunk order keeps the outcome independent of timing.
template <typename Body>
void forChunks(uint32_t begin, uint32_t end, uint32_t parts, const Body& body) {
  std::vector<std::thread> workers;
  uint32_t size = divideRoundUp(end - begin, parts);
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
      uint32_t count = static_cast<uint32_t>(refs_.size());
      Subtree tree = buildRange(0, count, 0, rangeBounds(0, count));
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
  Subtree buildRange(uint32_t begin, uint32_t end, uint32_t depth, const RangeBounds& bounds) {
    if (end - begin < kParallelSubtree) return buildSequential(begin, end, depth, bounds);
    BvhNode root;
    Split split;
    uint32_t middle = splitRange(begin, end, depth, bounds, root, split);
    if (middle == end) return {{root}, depth};
    Subtree left;
    std::thread worker;
    if (spareThreads_.fetch_sub(1) > 0) {
      worker = std::thread([&] { left = buildRange(begin, middle, depth + 1, split.left); });
    } else {
      spareThreads_.fetch_add(1);
      left = buildRange(begin, middle, depth + 1, split.left);
    }
    Subtree right = buildRange(middle, end, depth + 1, split.right);
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
    for (size_t i = 1; i < left.nodes.size(); ++i) {
      out.nodes.push_back(moved(left.nodes[i], leftOffset));
    }
    for (size_t i = 1; i < right.nodes.size(); ++i) {
      out.nodes.push_back(moved(right.nodes[i], rightOffset));
    }
    return out;
  }

  Subtree buildSequential(uint32_t begin, uint32_t end, uint32_t depth, const RangeBounds& bounds) {
    struct Task {
      uint32_t node, begin, end, depth;
      RangeBounds bounds;
    };
    Subtree out;
    out.nodes.reserve(2 * (end - begin) / options_.maxLeafSize + 1);
    out.nodes.emplace_back();
    std::vector<Task> tasks{{0, begin, end, depth, bounds}};
    while (!tasks.empty()) {
      Task task = tasks.back();
      tasks.pop_back();
      out.depth = std::max(out.depth, task.depth);
      BvhNode node;
      Split split;
      uint32_t middle = splitRange(task.begin, task.end, task.depth, task.bounds, node, split);
      if (middle != task.end) {
        node.firstIndex = static_cast<uint32_t>(out.nodes.size());
        node.count = 0;
        out.nodes.emplace_back();
        out.nodes.emplace_back();
        tasks.push_back({node.firstIndex + 1, middle, task.end, task.depth + 1, split.right});
        tasks.push_back({node.firstIndex, task.begin, middle, task.depth + 1, split.left});
      }
      out.nodes[task.node] = node;
    }
    return out;
  }

  // Fills `node` with the range's bounds; either makes it a leaf (returns
  // end) or partitions the range and returns where the right half starts,
  // with both halves' bounds in `split`.
  uint32_t splitRange(uint32_t begin, uint32_t end, uint32_t depth, const RangeBounds& bounds,
                      BvhNode& node, Split& split) {
    uint32_t count = end - begin;
    node.bounds = bounds.boxes;
    node.firstIndex = begin;
    node.count = count;
    if (count == 1 || depth >= options_.maxDepth) return end;
    // A split costs at least the node visit: no range up to that size is
    // worth binning when it may be a leaf.
    if (count <= options_.maxLeafSize && static_cast<float>(count) <= options_.traversalCost) {
      return end;
    }
    split = findSplit(begin, end, bounds);
    bool leafIsCheaper = split.axis < 0 || split.cost >= static_cast<float>(count);
    if (count <= options_.maxLeafSize && leafIsCheaper) return end;
    if (split.axis < 0) {
      // All centroids equal: any halving will do.
      uint32_t middle = begin + count / 2;
      split.left = rangeBounds(begin, middle);
      split.right = rangeBounds(middle, end);
      return middle;
    }
    return partition(begin, end, mappingFor(bounds, count), split);
  }

  // Moves the range's left-side references before its right-side ones (in
  // one sweep from both ends) and gathers each side's centroid bounds.
  uint32_t partition(uint32_t begin, uint32_t end, const BinMapping& mapping, Split& split) {
    uint32_t low = begin;
    uint32_t high = end;
    Bin sides[2];  // centroid bounds of the left and right side
    while (low < high) {
      Float4 c = load4(&refs_[low].box.min.x) + load4(&refs_[low].box.max.x);
      bool left = mapping(glm::vec3(c[0], c[1], c[2]), split.axis) < split.bin;
      Bin& side = sides[left ? 0 : 1];
      side.min = min4(side.min, c);
      side.max = max4(side.max, c);
      if (left) {
        ++low;
      } else {
        --high;
        std::swap(refs_[low], refs_[high]);
      }
    }
    split.left.centroids = sides[0].bounds();
    split.right.centroids = sides[1].bounds();
    return low;
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

  // Small ranges use fewer bins (no more than they have primitives, at
  // least 4): cheaper, and as good.
  BinMapping mappingFor(const RangeBounds& bounds, uint32_t count) const {
    uint32_t bins = std::min(std::max(count, 4u), options_.binCount);
    glm::vec3 extent = bounds.centroids.max - bounds.centroids.min;
    glm::vec3 scale(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
      if (extent[axis] > 0.0f) scale[axis] = static_cast<float>(bins) / extent[axis];
    }
    return {bounds.centroids.min, scale, bins};
  }

  void binRange(uint32_t from, uint32_t to, const BinMapping& mapping, AxisBins& bins) const {
    const Float4 origin = {mapping.origin.x, mapping.origin.y, mapping.origin.z, 0.0f};
    const Float4 scale = {mapping.scale.x, mapping.scale.y, mapping.scale.z, 0.0f};
    const Float4 zero = {0.0f, 0.0f, 0.0f, 0.0f};
    const float last = static_cast<float>(mapping.bins - 1);
    for (uint32_t i = from; i < to; ++i) {
      const PrimRef& ref = refs_[i];
      // min.xyz then max.x, and max.xyz then the index: only lanes x..z are used.
      Float4 low = load4(&ref.box.min.x);
      Float4 high = load4(&ref.box.max.x);
      Float4 position = max4((low + high - origin) * scale, zero);
      for (int axis = 0; axis < 3; ++axis) {
        Bin& bin = bins[axis][static_cast<uint32_t>(std::min(position[axis], last))];
        bin.min = min4(bin.min, low);
        bin.max = max4(bin.max, high);
        bin.count++;
      }
    }
  }

  // Best SAH split over binned centroid positions on all three axes, all
  // binned in one pass over the range (in chunks on several threads when
  // the range is large; bins merge exactly, so the result is the same).
  Split findSplit(uint32_t begin, uint32_t end, const RangeBounds& bounds) const {
    BinMapping mapping = mappingFor(bounds, end - begin);
    // Most nodes are small: reuse one set of bins per thread and clear only
    // the bins in use, instead of building thousands of bytes per node.
    thread_local AxisBins bins;
    for (auto& axisBins : bins) std::fill_n(axisBins.begin(), mapping.bins, Bin{});
    uint32_t parts = chunksFor(end - begin);
    if (parts == 1) {
      binRange(begin, end, mapping, bins);
    } else {
      std::vector<AxisBins> partial(parts);
      forChunks(begin, end, parts, [&](uint32_t part, uint32_t from, uint32_t to) {
        binRange(from, to, mapping, partial[part]);
      });
      for (const AxisBins& part : partial) {
        for (int axis = 0; axis < 3; ++axis) {
          for (uint32_t b = 0; b < mapping.bins; ++b) {
            bins[axis][b].min = min4(bins[axis][b].min, part[axis][b].min);
            bins[axis][b].max = max4(bins[axis][b].max, part[axis][b].max);
            bins[axis][b].count += part[axis][b].count;
          }
        }
      }
    }
    Split best;
    float parentArea = std::max(bounds.boxes.surfaceArea(), 1e-30f);
    for (int axis = 0; axis < 3; ++axis) {
      if (mapping.scale[axis] > 0.0f) {
        evaluateBins(bins[axis], mapping.bins, axis, parentArea, best);
      }
    }
    return best;
  }

  // Surface area of a box in bin lanes; only called on boxes that hold
  // something (an empty one would give inf or NaN).
  static float surfaceArea(Float4 min, Float4 max) {
    Float4 d = max - min;
    return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
  }

  // SAH sweep over one axis's bins; the winner's two sides get their
  // bounds merged from the bins once, after the sweep.
  void evaluateBins(const std::array<Bin, kMaxBins>& binned, uint32_t bins, int axis,
                    float parentArea, Split& best) const {
    thread_local std::array<float, kMaxBins> rightCost;
    thread_local std::array<uint32_t, kMaxBins> rightCount;
    Bin right;
    for (uint32_t b = bins - 1; b > 0; --b) {
      right.min = min4(right.min, binned[b].min);
      right.max = max4(right.max, binned[b].max);
      right.count += binned[b].count;
      rightCount[b] = right.count;
      if (right.count > 0) {
        rightCost[b] = surfaceArea(right.min, right.max) * static_cast<float>(right.count);
      }
    }
    Bin left;
    int bestBin = -1;
    for (uint32_t b = 0; b + 1 < bins; ++b) {
      left.min = min4(left.min, binned[b].min);
      left.max = max4(left.max, binned[b].max);
      left.count += binned[b].count;
      if (left.count == 0 || rightCount[b + 1] == 0) continue;
      float cost =
          options_.traversalCost +
          (surfaceArea(left.min, left.max) * static_cast<float>(left.count) + rightCost[b + 1]) /
              parentArea;
      if (cost < best.cost) {
        best.cost = cost;
        bestBin = static_cast<int>(b + 1);
      }
    }
    if (bestBin < 0) return;
    best.axis = axis;
    best.bin = static_cast<uint32_t>(bestBin);
    Bin sides[2];
    for (uint32_t b = 0; b < bins; ++b) {
      Bin& side = sides[b < best.bin ? 0 : 1];
      side.min = min4(side.min, binned[b].min);
      side.max = max4(side.max, binned[b].max);
    }
    best.left = {sides[0].bounds(), {}};
    best.right = {sides[1].bounds(), {}};
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

std::vector<Aabb> triangleBounds(const std::vector<glm::vec3>& positions,
                                 const std::vector<glm::uvec3>& faces) {
  std::vector<Aabb> boxes;
  boxes.reserve(faces.size());
  for (glm::uvec3 face : faces) {
    Aabb box;
    for (uint32_t corner : {face.x, face.y, face.z}) box.grow(positions[corner]);
    boxes.push_back(box);
  }
  return boxes;
}

}  // namespace rt
