#include "render/ProgressiveRenderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/AdaptiveSampling.hpp"
#include "util/Arithmetic.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// A stride coprime with `count` near count / golden ratio: g -> g * stride
// mod count is a permutation that sends any run of consecutive g to blocks
// spread evenly over 0..count-1 (a Weyl sequence).
uint32_t spreadingStride(uint32_t count) {
  if (count <= 2) return 1;
  const auto target = static_cast<uint32_t>(std::lround(0.6180339887 * count));
  for (uint32_t offset = 0;; ++offset) {
    for (uint32_t candidate : {target - offset, target + offset}) {
      if (candidate > 0 && candidate < count && std::gcd(candidate, count) == 1) return candidate;
    }
  }
}

// Workgroups a render dispatch with a work queue launches: each driver
// thread's share starts with one whose subgroups take runs until the queue
// is empty (the rest of the share finds it so), on up to 64 threads; past
// that, threads without a workgroup would idle.
constexpr uint32_t kQueueWorkgroups = 64;

// Buffers filled by transfers are read and written by the kernels after them.
void recordFillsBeforeKernels(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
}

// Accumulation buffers: storage buffers to the render kernel, the viewer's
// display pass and the noise measurement, and cleared and read back by
// transfers.
constexpr VkBufferUsageFlags kAccumulationUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

// The largest memory heap: no single allocation can exceed it.
VkDeviceSize largestHeap(const VulkanContext& context) {
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(context.physicalDevice(), &memory);
  VkDeviceSize largest = 0;
  for (uint32_t i = 0; i < memory.memoryHeapCount; ++i) {
    largest = std::max(largest, memory.memoryHeaps[i].size);
  }
  return largest;
}

// One vec4 per pixel in one storage buffer; an image beyond what the device
// can bind or allocate is refused up front with the numbers, not left to a
// failing vkAllocateMemory.
uint32_t gpuSamplerKind(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::Random: return RT_SAMPLER_RANDOM;
    case SamplerKind::Jittered: return RT_SAMPLER_JITTERED;
    case SamplerKind::Sobol: return RT_SAMPLER_SOBOL;
  }
  return RT_SAMPLER_RANDOM;
}

VkDeviceSize accumulationBytes(VulkanContext& context, const FlatScene& flat) {
  const VkDeviceSize bytes = VkDeviceSize(flat.info.width) * flat.info.height * sizeof(glm::vec4);
  const VkDeviceSize limit = std::min<VkDeviceSize>(
      VkDeviceSize(context.limits().maxStorageBufferRange), largestHeap(context));
  if (bytes > limit) {
    throw Error(fmt::format(
        "image {}x{} is too large for this device: its accumulation buffer needs {} MiB "
        "({} bytes per pixel), the device allows {} MiB in one buffer, i.e. at most {} pixels",
        flat.info.width, flat.info.height, bytes >> 20, sizeof(glm::vec4), limit >> 20,
        limit / sizeof(glm::vec4)));
  }
  return bytes;
}

ShaderFeatures featuresFor(const Scene& scene, const FlatScene& flat,
                           const ProgressiveOptions& options, const VulkanContext& context) {
  ShaderFeatures features = detectFeatures(scene, flat, options.adaptive);
  features.storageBuffers = options.sceneArrays == SceneArrays::StorageBuffers;
  features.shadowPairs &= options.walks == Walks::Paired;
  features.primaryPairs &= options.walks == Walks::Paired;
  features.countRays = options.countRays;
  features.countRaysPerSubgroup = options.countRays && context.subgroupArithmetic();
  features.samplerKind = static_cast<int>(gpuSamplerKind(options.sampler));
  features.adaptiveSampling = options.adaptive;
  features.oddSums = options.oddSums;
  features.workQueue = options.workQueue == WorkQueue::OnCpu && workQueueAvailable(context);
  features.laneVotes = laneVotesPay(context);
  return features;
}

FlattenOptions flattenOptionsFor(const ProgressiveOptions& options) {
  FlattenOptions flatten;
  flatten.width = options.width;
  flatten.height = options.height;
  flatten.shading = options.shading;
  flatten.accel = options.accel;
  flatten.frameOrigin = options.frameOrigin;
  flatten.displayMapping = options.displayMapping;
  return flatten;
}

// Debian 12's own lavapipe (Mesa 22.3), where the CPU paths below do not pay
// or are miscompiled.
bool lavapipeBefore25(const VulkanContext& context) {
  const std::optional<uint32_t> mesa = context.lavapipeMesaMajor();
  return mesa && *mesa < 25;
}

// `options` with the scene arrays this device reads right.
ProgressiveOptions withReadableSceneArrays(ProgressiveOptions options,
                                           const VulkanContext& context) {
  options.sceneArrays = readableSceneArrays(context, options.sceneArrays);
  return options;
}

}  // namespace

// Mesa 22.3's lavapipe miscompiles the loop around the pixels (some pixels
// of a pass lose samples: Debian 12's own driver, seen in the sample counts
// of EXR outputs); Mesa 25's renders them bit for bit as the grid does.
bool workQueueAvailable(const VulkanContext& context) {
  return context.isCpu() && context.subgroupBallot() && !lavapipeBefore25(context);
}

// Mesa 22.3's lavapipe gains nothing from the vote and pays for it: the
// common scene rendered 0.82x as fast with it there (1.07x on Mesa 25).
bool laneVotesPay(const VulkanContext& context) {
  return context.subgroupVote() && !lavapipeBefore25(context);
}

ProgressiveRenderer::ProgressiveRenderer(VulkanContext& context, const ShaderCompiler& compiler,
                                         const Scene& scene, const ProgressiveOptions& options)
    : context_(context),
      compiler_(compiler),
      options_(withReadableSceneArrays(options, context)),
      flat_(flattenScene(scene, flattenOptionsFor(options))),
      features_(featuresFor(scene, flat_, options_, context)),
      width_(flat_.info.width),
      height_(flat_.info.height),
      sceneBuffers_(context, flat_, options_.sceneArrays),
      region_(resolveRegion(options.region, width_, height_)),
      accumulation_(context, accumulationBytes(context, flat_), kAccumulationUsage) {
  accumulation_.fillZero();
  warnings_ = flat_.warnings;
  if (options_.sceneArrays != options.sceneArrays) {
    warnings_.push_back(fmt::format(
        "lavapipe at {}-bit vectors (LP_NATIVE_VECTOR_WIDTH) misreads texel buffers; the scene "
        "is read from storage buffers instead (--scene-arrays storage: the same image, slower)",
        context.subgroupSize() * 32));
  }
  if (options.oddSums) {
    oddAccumulation_.emplace(context, accumulation_.size(), kAccumulationUsage);
    oddAccumulation_->fillZero();
  }
  samplesDone_ = options.firstSample;
  if (options.countRays) {
    rayCounter_.emplace(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    rayCounter_->fillZero();
  }
  if (features_.workQueue) {
    workQueue_.emplace(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    workQueue_->fillZero();
  }
  if (options.adaptive) {
    const glm::uvec2 grid = gpu::adaptiveTileGrid({width_, height_});
    const uint32_t tiles = grid.x * grid.y;
    samplePlan_.emplace(context, VkDeviceSize(tiles) * sizeof(glm::uvec2),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    samplePlan_->fillZero();
    tileRays_.emplace(context, VkDeviceSize(tiles) * sizeof(uint32_t),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    tileRays_->fillZero();
    tileRaysRead_.assign(tiles, 0);
    pixelExtras_.emplace(context, VkDeviceSize(width_) * height_ * sizeof(uint32_t),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    pixelExtras_->fillZero();
  }
  kernel_ = buildKernel();
  // Made now where the render will measure its noise, so that the pipeline's
  // compile counts as setup, not rendering.
  if (options.independentHalves) {
    tileNoise_ = std::make_unique<TileNoiseKernel>(context, compiler, width_, height_);
  }
}

std::vector<KernelBinding> ProgressiveRenderer::kernelBindings(const ShaderFeatures& features,
                                                               AccelKind accel) {
  std::vector<KernelBinding> bindings = SceneBuffers::bindings(
      accel, features.storageBuffers ? SceneArrays::StorageBuffers : SceneArrays::TexelBuffers);
  bindings.push_back({RT_BINDING_ACCUMULATION});
  bindings.push_back({RT_BINDING_ACCUMULATION_ODD});
  if (features.countRays) bindings.push_back({RT_BINDING_RAY_COUNTER});
  if (features.workQueue) bindings.push_back({RT_BINDING_WORK_QUEUE});
  if (features.adaptiveSampling) {
    bindings.push_back({RT_BINDING_SAMPLE_PLAN});
    bindings.push_back({RT_BINDING_TILE_RAYS});
    bindings.push_back({RT_BINDING_PIXEL_EXTRAS});
  }
  return bindings;
}

std::unique_ptr<ComputeKernel> ProgressiveRenderer::buildKernel() const {
  auto kernel = std::make_unique<ComputeKernel>(
      context_, compiler_.compile("trace.comp", features_.defines()),
      kernelBindings(features_, flat_.accel), static_cast<uint32_t>(sizeof(gpu::GpuFrameParams)));
  sceneBuffers_.bindTo(*kernel);
  kernel->bind(RT_BINDING_ACCUMULATION, accumulation_);
  // Without odd sums the kernel does not declare the binding: it stays unwritten.
  if (oddAccumulation_) kernel->bind(RT_BINDING_ACCUMULATION_ODD, *oddAccumulation_);
  if (rayCounter_) kernel->bind(RT_BINDING_RAY_COUNTER, *rayCounter_);
  if (workQueue_) kernel->bind(RT_BINDING_WORK_QUEUE, *workQueue_);
  if (samplePlan_) kernel->bind(RT_BINDING_SAMPLE_PLAN, *samplePlan_);
  if (tileRays_) kernel->bind(RT_BINDING_TILE_RAYS, *tileRays_);
  if (pixelExtras_) kernel->bind(RT_BINDING_PIXEL_EXTRAS, *pixelExtras_);
  // In setup, not in the render's time: an empty tile, where every
  // invocation returns at once.
  const gpu::GpuFrameParams emptyTile{};
  kernel->compileNow(&emptyTile);
  return kernel;
}

void ProgressiveRenderer::recordSamples(VkCommandBuffer commands, uint32_t row, uint32_t rows,
                                        uint32_t count) const {
  if (samplePlan_) throw Error("an adaptive render kernel takes its samples from the plan");
  recordRange(commands, row, rows, samplesDone_, count);
}

void ProgressiveRenderer::setSamplePlan(const std::vector<glm::uvec2>& ranges,
                                        const std::vector<uint32_t>& pixelExtras) {
  if (!samplePlan_ || ranges.size() * sizeof(glm::uvec2) != samplePlan_->size()) {
    throw Error("sample plan: not an adaptive render, or not one range per tile");
  }
  samplePlan_->upload(ranges.data(), samplePlan_->size());
  if (pixelExtras.empty()) return;
  if (pixelExtras.size() * sizeof(uint32_t) != pixelExtras_->size()) {
    throw Error("sample plan: not one edge count per pixel");
  }
  pixelExtras_->upload(pixelExtras.data(), pixelExtras_->size());
}

void ProgressiveRenderer::recordPlannedSamples(VkCommandBuffer commands, uint32_t row,
                                               uint32_t rows) const {
  if (!samplePlan_) throw Error("sample plan: not an adaptive render");
  // The push constant's range is unused: the kernel reads each tile's own.
  recordRange(commands, row, rows, 0, 0);
}

void ProgressiveRenderer::recordRange(VkCommandBuffer commands, uint32_t row, uint32_t rows,
                                      uint32_t first, uint32_t count) const {
  gpu::GpuFrameParams frame{};
  frame.tileOrigin = {region_.x, region_.y + row};
  frame.tileSize = {region_.width, rows};
  frame.sampleBegin = first;
  frame.sampleCount = count;
  frame.samplesTotal = std::max(options_.samplesTotal, first + count);
  frame.seed = options_.seed;
  frame.samplerKind = gpuSamplerKind(options_.sampler);
  if (options_.independentHalves) frame.samplerKind |= RT_SAMPLER_REPLICATES;
  const glm::uvec2 groups{divideRoundUp(region_.width, RT_WORKGROUP_SIZE_X),
                          divideRoundUp(rows, RT_WORKGROUP_SIZE_Y)};
  if (!workQueue_) {
    frame.groupStride = {spreadingStride(groups.x), spreadingStride(groups.y)};
    kernel_->recordDispatch(commands, &frame, groups.x, groups.y);
    return;
  }
  // The queue starts empty; a few workgroups take all its runs (the first
  // of each driver thread's share does, the others find it empty).
  vkCmdFillBuffer(commands, workQueue_->handle(), 0, VK_WHOLE_SIZE, 0);
  recordFillsBeforeKernels(commands);
  kernel_->recordDispatch(commands, &frame, std::min(groups.x * groups.y, kQueueWorkgroups), 1);
}

void ProgressiveRenderer::addSamples(uint32_t count) {
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { recordSamples(commands, 0, region_.height, count); });
  finishPass(count);
}

void ProgressiveRenderer::recordReset(VkCommandBuffer commands) {
  resetSinceMeasured_ = true;
  vkCmdFillBuffer(commands, accumulation_.handle(), 0, VK_WHOLE_SIZE, 0);
  if (oddAccumulation_) vkCmdFillBuffer(commands, oddAccumulation_->handle(), 0, VK_WHOLE_SIZE, 0);
  // The noise measurement reads the extras of every pixel of an adaptive
  // render: none until an edge round renders some.
  if (pixelExtras_) vkCmdFillBuffer(commands, pixelExtras_->handle(), 0, VK_WHOLE_SIZE, 0);
  if (tileRays_) {
    vkCmdFillBuffer(commands, tileRays_->handle(), 0, VK_WHOLE_SIZE, 0);
    std::fill(tileRaysRead_.begin(), tileRaysRead_.end(), 0u);
  }
  recordFillsBeforeKernels(commands);
  samplesDone_ = options_.firstSample;
}

void ProgressiveRenderer::reset() {
  context_.submitAndWait([&](VkCommandBuffer commands) { recordReset(commands); });
}

void ProgressiveRenderer::setCamera(const Camera& camera) {
  fillCamera(camera, width_, height_, flat_.frame, flat_.info);
  sceneBuffers_.updateInfo(flat_.info);
  reset();
}

void ProgressiveRenderer::reloadShaders() {
  // Both compile before either is replaced: an error leaves both as they were.
  std::unique_ptr<ComputeKernel> fresh = buildKernel();
  std::unique_ptr<TileNoiseKernel> freshNoise;
  if (tileNoise_) {
    freshNoise = std::make_unique<TileNoiseKernel>(context_, compiler_, width_, height_);
  }
  retired_.push_back(std::move(kernel_));
  kernel_ = std::move(fresh);
  // The noise kernel runs only between dispatches (measure waits): no frame uses it now.
  if (freshNoise) tileNoise_ = std::move(freshNoise);
}

ImageF ProgressiveRenderer::resolve() {
  std::vector<glm::vec4> sums(size_t(width_) * height_);
  accumulation_.download(sums.data(), sums.size() * sizeof(glm::vec4));
  ImageF image{width_, height_, {}};
  image.rgba.resize(sums.size() * 4);
  for (size_t i = 0; i < sums.size(); ++i) {
    float count = std::max(sums[i].w, 1.0f);
    image.rgba[i * 4 + 0] = sums[i].x / count;
    image.rgba[i * 4 + 1] = sums[i].y / count;
    image.rgba[i * 4 + 2] = sums[i].z / count;
    image.rgba[i * 4 + 3] = sums[i].w;  // samples behind the mean, for merging
  }
  return image;
}

SampleSums ProgressiveRenderer::sampleSums() {
  SampleSums sums{width_, height_, {}, {}};
  sums.all.resize(size_t(width_) * height_);
  sums.odd.resize(sums.all.size());  // zeros without odd sums
  accumulation_.download(sums.all.data(), sums.all.size() * sizeof(glm::vec4));
  if (oddAccumulation_) {
    oddAccumulation_->download(sums.odd.data(), sums.odd.size() * sizeof(glm::vec4));
  }
  return sums;
}

bool ProgressiveRenderer::halvesIndependent() const {
  return options_.oddSums &&
         (options_.independentHalves || options_.sampler == SamplerKind::Random);
}

std::optional<double> ProgressiveRenderer::estimateRmse(const ToneMapping& mapping) {
  if (!halvesIndependent()) return std::nullopt;
  return estimatedRmse(tileNoise(mapping), uint64_t(region_.width) * region_.height);
}

std::vector<gpu::GpuTileNoise> ProgressiveRenderer::tileNoise(const ToneMapping& mapping) {
  return measureTiles(mapping, nullptr);
}

std::vector<gpu::GpuTileNoise> ProgressiveRenderer::measureTiles(
    const ToneMapping& mapping, const std::vector<uint32_t>* roundTiles) {
  if (!halvesIndependent())
    throw Error("tile noise: the halves of this render are not independent");
  if (!tileNoise_) {
    tileNoise_ = std::make_unique<TileNoiseKernel>(context_, compiler_, width_, height_);
  }
  // Without other changes since the last measurement, only the round's
  // tiles changed.
  const std::vector<uint32_t>* changed = resetSinceMeasured_ ? nullptr : roundTiles;
  std::vector<gpu::GpuTileNoise> tiles =
      tileNoise_->measure(accumulation_, *oddAccumulation_, pixelExtras_ ? &*pixelExtras_ : nullptr,
                          region_, mapping, changed);
  resetSinceMeasured_ = false;
  return tiles;
}

void ProgressiveRenderer::finishAdaptiveRound(AdaptiveRounds& rounds, const ToneMapping& mapping) {
  const AdaptiveRounds::ImageReader image{[this] { return sampleSums(); }, mapping};
  const std::vector<uint32_t> roundTiles = rounds.roundTiles();
  rounds.finishRound(measureTiles(mapping, &roundTiles), takeTileRays(), &image);
}

void ProgressiveRenderer::stopAdaptiveRound(AdaptiveRounds& rounds, const ToneMapping& mapping) {
  const std::vector<uint32_t> roundTiles = rounds.roundTiles();
  rounds.measureStop(measureTiles(mapping, &roundTiles));
}

std::vector<uint32_t> ProgressiveRenderer::takeTileRays() {
  if (!tileRays_) throw Error("tile rays: not an adaptive render");
  std::vector<uint32_t> counters(tileRaysRead_.size());
  tileRays_->download(counters.data(), tileRays_->size());
  // The counters run on; unsigned differences are exact across a wrap as
  // long as one round adds fewer than 2^32 rays to a tile.
  std::vector<uint32_t> rays(counters.size());
  for (size_t i = 0; i < rays.size(); ++i) rays[i] = counters[i] - tileRaysRead_[i];
  tileRaysRead_ = std::move(counters);
  return rays;
}

uint64_t ProgressiveRenderer::raysTraced() {
  if (!rayCounter_) return 0;
  // The 32-bit counter is folded into 64 bits and cleared whenever it is
  // read, so it cannot overflow as long as it is read every few dispatches.
  uint32_t count = 0;
  rayCounter_->download(&count, sizeof(count));
  raysTraced_ += count;
  rayCounter_->fillZero();
  return raysTraced_;
}

}  // namespace rt
