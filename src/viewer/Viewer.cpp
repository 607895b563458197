#include "viewer/Viewer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <utility>

#include "formats/SceneFile.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/BatchIntersector.hpp"
#include "scene/SceneBounds.hpp"
#include "util/Error.hpp"
#include "viewer/DisplayPass.hpp"
#include "viewer/Swapchain.hpp"
#include "viewer/SwapchainReadback.hpp"

namespace rt::viewer {
namespace {

constexpr uint32_t kDefaultSamples = 16;  // as `raytracer SCENE OUT`
constexpr uint64_t kFenceTimeoutNs = 600ull * 1000 * 1000 * 1000;
// A new window size is rendered once it held this long (drags resize often).
constexpr std::chrono::milliseconds kResizeSettle(250);
// Without --verbose, a progress line at most this often.
constexpr std::chrono::seconds kLogInterval(1);
// An idle viewer checks for file changes this often, and redraws (for the
// overlay's statistics) at least this often.
constexpr std::chrono::milliseconds kIdleWait(25);
constexpr std::chrono::milliseconds kIdleRedraw(500);

volatile std::sig_atomic_t gSignalled = 0;

void onSignal(int) { gSignalled = 1; }

// SIGINT and SIGTERM end the session like closing the window: the last
// frame is still presented (and its screenshot written) before exiting.
void installSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

double millisecondsBetween(std::chrono::steady_clock::time_point a,
                           std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

ContextOptions contextOptions(const ViewerOptions& options, const Window& window) {
  ContextOptions context;
  context.validation = options.validation;
  context.deviceIndex = options.deviceIndex;
  context.instanceExtensions = Window::requiredInstanceExtensions();
  context.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  context.createSurface = [&window](VkInstance instance) { return window.createSurface(instance); };
  return context;
}

VkExtent2D toExtent(glm::uvec2 size) { return {size.x, size.y}; }

}  // namespace

void RateMeter::add(double samples, Clock::time_point now) {
  samples_ += samples;
  double seconds = std::chrono::duration<double>(now - start_).count();
  if (seconds < 1.0) return;
  rate_ = samples_ / seconds;
  samples_ = 0.0;
  start_ = now;
}

Scene Viewer::loadViewedScene() const {
  Scene scene = loadSceneFile(options_.scenePath);
  if (options_.conventions) setConventions(scene, *options_.conventions, "--conventions");
  return scene;
}

ToneMapping Viewer::displayMapping() const {
  ToneMapping mapping = toneMappingFor(scene_);
  mapping.exposure = settings_.exposure;
  return mapping;
}

Viewer::Viewer(const ViewerOptions& options)
    : options_(options), accumulation_(options.frameSeconds, options.samplesPerFrame) {
  scene_ = loadViewedScene();
  for (const std::string& warning : scene_.warnings) {
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  }
  if (!options_.cameraPath.empty()) path_ = CameraPathPlayer(loadCameraPath(options_.cameraPath));
  uint32_t width = options_.width ? options_.width : scene_.camera.width;
  uint32_t height = options_.height ? options_.height : scene_.camera.height;
  window_ = std::make_unique<Window>(width, height,
                                     "raytracer - " + options_.scenePath.filename().string());
  context_ = std::make_unique<VulkanContext>(contextOptions(options_, *window_));
  compiler_ = std::make_unique<ShaderCompiler>(
      options_.shaderDir.empty() ? ShaderCompiler::defaultShaderDir() : options_.shaderDir,
      ShaderCompiler::defaultCacheDir());
  swapchain_ = std::make_unique<Swapchain>(*context_);
  swapchain_->recreate(toExtent(window_->framebufferSize()));
  display_ = std::make_unique<DisplayPass>(*context_, *compiler_);
  overlay_ = std::make_unique<Overlay>(*window_, *context_, *swapchain_);
  overlay_->setVisible(options_.overlay);
  readback_ = std::make_unique<SwapchainReadback>(*context_);
  createFrameObjects();
  initialiseSettings();

  glm::uvec2 size{swapchain_->extent().width, swapchain_->extent().height};
  useRenderer(makeRenderer(size));  // errors end the viewer before it starts
  renderSizeWanted_ = size;
  if (options_.watch) startWatching();
  std::printf("viewer: %ux%u on %s, scene %s, shaders %s\n", size.x, size.y,
              context_->description().summary().c_str(), options_.scenePath.string().c_str(),
              compiler_->shaderDir().string().c_str());
}

Viewer::~Viewer() {
  if (context_) vkDeviceWaitIdle(context_->device());
  destroyFrameObjects();
}

void Viewer::initialiseSettings() {
  BoundingSphere bounds = boundingSphere(scene_);
  camera_.setHome(scene_.camera, bounds.center, bounds.radius);
  uint32_t fromScene = scene_.settings.samplesPerPixel;
  settings_.samplesTarget = static_cast<int>(
      options_.samplesTarget ? *options_.samplesTarget : (fromScene ? fromScene : kDefaultSamples));
  settings_.bounces = static_cast<int>(scene_.settings.maxBounces);
  settings_.indirectClamp = scene_.settings.indirectClamp;
  settings_.adaptive = options_.adaptive || scene_.settings.adaptive;
  // As the render command: adaptive renders default to Sobol.
  SamplerKind fallback = settings_.adaptive && !scene_.settings.samplerGiven
                             ? SamplerKind::Sobol
                             : scene_.settings.sampler;
  SamplerKind sampler = options_.sampler.value_or(fallback);
  settings_.sampler = static_cast<int>(sampler);
  settings_.exposure = toneMappingFor(scene_).exposure * options_.exposure;
  settings_.apertureRadius = camera_.camera().apertureRadius;
  settings_.focusDistance = camera_.camera().focusDistance;
  settings_.lensScale = static_cast<float>(bounds.radius);
}

void Viewer::createFrameObjects() {
  VkDevice device = context_->device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context_->queueFamily();
  vkCheck(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool_), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = commandPool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  vkCheck(vkAllocateCommandBuffers(device, &allocInfo, &commands_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCheck(vkCreateFence(device, &fenceInfo, nullptr, &frameFence_), "vkCreateFence");
  VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  vkCheck(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &imageAcquired_), "vkCreateSemaphore");
}

void Viewer::destroyFrameObjects() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (imageAcquired_) vkDestroySemaphore(device, imageAcquired_, nullptr);
  if (frameFence_) vkDestroyFence(device, frameFence_, nullptr);
  if (commandPool_) vkDestroyCommandPool(device, commandPool_, nullptr);
  imageAcquired_ = VK_NULL_HANDLE;
  frameFence_ = VK_NULL_HANDLE;
  commandPool_ = VK_NULL_HANDLE;
}

void Viewer::startWatching() {
  watcher_ = std::make_unique<FileWatcher>();
  watcher_->watchFolder(compiler_->shaderDir());
  std::filesystem::path sceneFolder = options_.scenePath.parent_path();
  watcher_->watchFolder(sceneFolder.empty() ? std::filesystem::path(".") : sceneFolder);
}

SamplerKind Viewer::samplerSetting() const {
  return static_cast<SamplerKind>(std::clamp(settings_.sampler, 0, 2));
}

std::unique_ptr<ProgressiveRenderer> Viewer::makeRenderer(glm::uvec2 size) const {
  Scene scene = scene_;
  scene.settings.maxBounces = static_cast<uint32_t>(settings_.bounces);
  scene.settings.indirectClamp = std::max(settings_.indirectClamp, 0.0f);
  scene.camera = camera_.camera();
  ProgressiveOptions options;
  options.width = size.x;
  options.height = size.y;
  options.samplesTotal = static_cast<uint32_t>(settings_.samplesTarget);
  options.seed = options_.seed;
  options.sampler = samplerSetting();
  options.shading = options_.shading;
  options.adaptive = settings_.adaptive;
  options.independentHalves = settings_.adaptive;  // the rounds' noise estimate
  return std::make_unique<ProgressiveRenderer>(*context_, *compiler_, scene, options);
}

void Viewer::useRenderer(std::unique_ptr<ProgressiveRenderer> renderer) {
  renderer_ = std::move(renderer);  // no frame in flight: the old one can go
  display_->setSource(renderer_->accumulation(), renderer_->width(), renderer_->height());
  restartAccumulation();
  rebuildFailed_ = false;
}

bool Viewer::rebuildRenderer(glm::uvec2 size) {
  frameBusy_ = true;
  try {
    useRenderer(makeRenderer(size));
    return true;
  } catch (const ShaderCompileError& e) {
    reportShaderError(e.what());
  } catch (const std::exception& e) {
    notice(fmt::format("render: error {}", e.what()));
  }
  // The current renderer goes on; retried once the shaders change.
  rebuildFailed_ = true;
  return false;
}

void Viewer::restartAccumulation() {
  accumulation_.restart(*renderer_, static_cast<uint32_t>(settings_.samplesTarget),
                        settings_.adaptive);
}

void Viewer::applyCameraChange() {
  if (!cameraChanged_) return;
  cameraChanged_ = false;
  const Camera& camera = camera_.camera();
  settings_.apertureRadius = camera.apertureRadius;
  settings_.focusDistance = camera.focusDistance;
  // The thin-lens code is compiled in only when the scene needs it.
  // Should that rebuild fail, the camera still moves (without the lens).
  bool needsLens = camera.type == CameraType::ThinLens && camera.apertureRadius > 0.0f;
  if (needsLens && !renderer_->features().thinLens &&
      rebuildRenderer({renderer_->width(), renderer_->height()})) {
    return;
  }
  renderer_->setCamera(camera);
  restartAccumulation();
}

void Viewer::applyResize() {
  glm::uvec2 current{renderer_->width(), renderer_->height()};
  if (renderSizeWanted_ == current || rebuildFailed_) return;
  // Scripted runs have no one dragging the window border: no need to wait.
  bool settled = Clock::now() - resizeSeenAt_ >= kResizeSettle || scripted();
  if (settled && rebuildRenderer(renderSizeWanted_)) {
    std::printf("resize: rendering at %ux%u\n", renderSizeWanted_.x, renderSizeWanted_.y);
  }
}

void Viewer::recreateSwapchain() {
  glm::uvec2 size = window_->framebufferSize();
  if (size.x == 0 || size.y == 0) return;  // minimised: wait for a size
  swapchain_->recreate(toExtent(size));
  overlay_->onSwapchainRecreated(*swapchain_);
  swapchainStale_ = false;
  glm::uvec2 extent{swapchain_->extent().width, swapchain_->extent().height};
  if (extent != renderSizeWanted_) {
    renderSizeWanted_ = extent;
    resizeSeenAt_ = Clock::now();
  }
}

int Viewer::run() {
  installSignalHandlers();
  bool lastFrameSubmitted = false;
  for (;;) {
    waitForFrame();
    if (lastFrameSubmitted) break;
    if (!prepareFrame()) continue;
    if (drawFrame()) {
      logFrame();
      if (quit_) lastFrameSubmitted = true;
    } else if (quit_ && window_->framebufferSize().x == 0) {
      std::fprintf(stderr, "warning: the window has no size; no last frame to show\n");
      break;
    }
  }
  vkDeviceWaitIdle(context_->device());
  if (context_->validationMessageCount() > 0) {
    std::fprintf(stderr, "error: %u Vulkan validation message(s) reported\n",
                 context_->validationMessageCount());
    return 1;
  }
  return 0;
}

bool Viewer::scripted() const { return options_.frames > 0 || !path_.finished(); }

bool Viewer::idle() const {
  return !scripted() && !accumulation_.accumulating() && !reloadSavedAt_ && !quit_;
}

bool Viewer::prepareFrame() {
  if (idle()) {
    // Nothing to render: sleep until input comes, a watched file changes or
    // the statistics are due for a refresh.
    window_->waitEvents(kIdleWait.count() * 1e-3);
  } else {
    window_->pollEvents();
  }
  quit_ = quit_ || window_->shouldClose() || gSignalled != 0 ||
          (options_.frames > 0 && framesPresented_ + 1 >= options_.frames);
  handleFileChanges();
  bool active = window_->takeActivity();
  if (idle() && !active && Clock::now() - lastPresentAt_ < kIdleRedraw) return false;

  if (const PathStep* step = path_.next()) applyPathStep(*step);
  handleInput(window_->takeInput(overlay_->wantsMouse(), overlay_->wantsKeyboard()));
  applyOverlayActions(overlay_->build(overlayStats(), settings_, messages_));
  applyCameraChange();
  applyResize();
  if (quit_ && !options_.screenshot.empty()) screenshots_.push_back(options_.screenshot);
  return true;
}

void Viewer::waitForFrame() {
  if (!frameInFlight_) return;
  vkCheck(vkWaitForFences(context_->device(), 1, &frameFence_, VK_TRUE, kFenceTimeoutNs),
          "vkWaitForFences");
  frameInFlight_ = false;
  Clock::time_point now = Clock::now();
  double seconds = std::chrono::duration<double>(now - lastFrameDone_).count();
  lastFrameDone_ = now;
  frameMilliseconds_ = seconds * 1e3;
  // Only plain rendering frames say how much work fits into one.
  if (submittedFrameRendered_ && !submittedFrameBusy_) accumulation_.frameTook(seconds);
  rate_.add(double(submittedPixelSamples_), now);

  if (submittedReloadSavedAt_) {
    // The first frame drawn with reloaded shaders is finished and presented.
    std::printf("reload: presented %.0f ms after the save\n",
                millisecondsBetween(*submittedReloadSavedAt_, now));
    submittedReloadSavedAt_.reset();
  }
  // Nothing is in flight now: the replaced kernels can go.
  renderer_->releaseRetiredKernels();
  display_->releaseRetired();
  if (!submittedScreenshots_.empty()) {
    try {
      readback_->write(submittedScreenshots_);
      for (const auto& path : submittedScreenshots_) std::printf("screenshot: %s\n", path.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
    }
    submittedScreenshots_.clear();
  }
}

bool Viewer::drawFrame() {
  glm::uvec2 size = window_->framebufferSize();
  VkExtent2D extent = swapchain_->extent();
  if (swapchainStale_ || size.x != extent.width || size.y != extent.height) recreateSwapchain();
  if (swapchainStale_ || size.x == 0 || size.y == 0) return false;

  uint32_t imageIndex = 0;
  VkResult acquired = vkAcquireNextImageKHR(context_->device(), swapchain_->handle(), UINT64_MAX,
                                            imageAcquired_, VK_NULL_HANDLE, &imageIndex);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    swapchainStale_ = true;
    return false;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) vkCheck(acquired, "vkAcquireNextImageKHR");

  vkCheck(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
  recordFrame(commands_, imageIndex);
  vkCheck(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");

  // The first use of the swapchain image is the blit's layout transition.
  VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSemaphore renderFinished = swapchain_->renderFinished(imageIndex);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &imageAcquired_;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &renderFinished;
  vkCheck(vkResetFences(context_->device(), 1, &frameFence_), "vkResetFences");
  vkCheck(vkQueueSubmit(context_->queue(), 1, &submit, frameFence_), "vkQueueSubmit");
  frameInFlight_ = true;
  submittedFrameBusy_ = frameBusy_;
  frameBusy_ = false;
  submittedScreenshots_ = std::move(screenshots_);
  screenshots_.clear();
  submittedReloadSavedAt_ = std::exchange(reloadSavedAt_, std::nullopt);

  VkSwapchainKHR swapchain = swapchain_->handle();
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &renderFinished;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &imageIndex;
  VkResult presented = vkQueuePresentKHR(context_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
      acquired == VK_SUBOPTIMAL_KHR) {
    swapchainStale_ = true;
  } else {
    vkCheck(presented, "vkQueuePresentKHR");
  }
  ++framesPresented_;
  lastPresentAt_ = Clock::now();
  return true;
}

void Viewer::recordFrame(VkCommandBuffer commands, uint32_t imageIndex) {
  RowRange rendered = recordRenderBands(commands);
  // Only rows that got samples change, unless the tone mapping itself did.
  if (displayStale_ || settings_.exposure != displayedExposure_) {
    rendered = {0, renderer_->height()};
    displayStale_ = false;
    displayedExposure_ = settings_.exposure;
  }
  display_->recordToneMap(commands, displayMapping(), rendered.first, rendered.count);
  VkImage image = swapchain_->image(imageIndex);
  VkExtent2D extent = swapchain_->extent();
  display_->recordBlit(commands, image, extent);

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = swapchain_->renderPass();
  pass.framebuffer = swapchain_->framebuffer(imageIndex);
  pass.renderArea = {{0, 0}, extent};
  vkCmdBeginRenderPass(commands, &pass, VK_SUBPASS_CONTENTS_INLINE);
  overlay_->record(commands);
  vkCmdEndRenderPass(commands);

  if (!screenshots_.empty()) {
    if (swapchain_->readable()) {
      readback_->record(commands, image, extent, swapchain_->format());
    } else {
      std::fprintf(stderr, "error: this window's images cannot be read back; no screenshot\n");
      screenshots_.clear();
    }
  }
}

Viewer::RowRange Viewer::recordRenderBands(VkCommandBuffer commands) {
  Accumulation::FrameSamples frame = accumulation_.record(commands, displayMapping());
  if (frame.readBack) frameBusy_ = true;
  submittedPixelSamples_ = frame.pixelSamples;
  submittedFrameRendered_ = frame.rows > 0;
  return {frame.firstRow, frame.rows};
}

void Viewer::logFrame() {
  Clock::time_point now = Clock::now();
  uint32_t target = static_cast<uint32_t>(settings_.samplesTarget);
  bool due = options_.verbose || now - lastLogAt_ >= kLogInterval;
  if (due && (submittedFrameRendered_ || options_.verbose)) {
    std::printf("frame %llu spp=%s/%u ms=%.1f msps=%.3f work=%llu\n",
                static_cast<unsigned long long>(framesPresented_),
                accumulation_.samplesText().c_str(), target, frameMilliseconds_,
                rate_.perSecond() * 1e-6, static_cast<unsigned long long>(submittedPixelSamples_));
    lastLogAt_ = now;
  }
  if (std::optional<double> seconds = accumulation_.takeDoneSeconds()) {
    std::printf("done: spp=%s in %.2f s (frame %llu)\n", accumulation_.samplesText().c_str(),
                *seconds, static_cast<unsigned long long>(framesPresented_));
  }
  std::fflush(stdout);
}

OverlayStats Viewer::overlayStats() const {
  OverlayStats stats;
  stats.samplesDone = accumulation_.samplesPerPixel();
  stats.adaptive = accumulation_.adaptive();
  stats.rmseEstimate = accumulation_.rmseEstimate();
  stats.samplesTarget = static_cast<uint32_t>(settings_.samplesTarget);
  stats.samplesPerSecond = rate_.perSecond();
  stats.frameMilliseconds = frameMilliseconds_;
  stats.renderSize = {renderer_->width(), renderer_->height()};
  stats.device = context_->description().name;
  stats.features = renderer_->features().summary();
  stats.scene = options_.scenePath.filename().string();
  return stats;
}

int runViewer(const ViewerOptions& options) {
  Viewer viewer(options);
  return viewer.run();
}

}  // namespace rt::viewer
