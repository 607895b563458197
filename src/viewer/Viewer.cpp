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
#include "viewer/FrameSync.hpp"
#include "viewer/Swapchain.hpp"
#include "viewer/SwapchainReadback.hpp"

namespace rt::viewer {
namespace {

constexpr uint32_t kDefaultSamples = 16;  // as `raytracer SCENE OUT`
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

Scene Viewer::loadViewedScene() const {
  Scene scene = loadSceneFile(options_.scenePath);
  if (options_.conventions) setConventions(scene, *options_.conventions, "--conventions");
  if (options_.toneCurve) scene.camera.toneCurve = *options_.toneCurve;
  if (options_.mode) scene.settings.mode = *options_.mode;
  if (options_.bounces) scene.settings.maxBounces = *options_.bounces;
  return scene;
}

ToneMapping Viewer::displayMapping() const {
  ToneMapping mapping = toneMappingFor(scene_);
  mapping.exposure = settings().exposure;
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
  frameSync_ = std::make_unique<FrameSync>(*context_);
  initialiseSettings();

  glm::uvec2 size{swapchain_->extent().width, swapchain_->extent().height};
  useRenderer(makeRenderer(size));  // errors end the viewer before it starts
  resize_.start(size);
  if (options_.watch)
    reload_ = std::make_unique<HotReload>(compiler_->shaderDir(), options_.scenePath);
  std::printf("viewer: %ux%u on %s, scene %s, shaders %s\n", size.x, size.y,
              context_->description().summary().c_str(), options_.scenePath.string().c_str(),
              compiler_->shaderDir().string().c_str());
}

Viewer::~Viewer() {
  if (context_) vkDeviceWaitIdle(context_->device());
}

void Viewer::initialiseSettings() {
  OverlaySettings& values = settings();
  BoundingSphere bounds = boundingSphere(scene_);
  camera_.setHome(scene_.camera, bounds.center, bounds.radius);
  uint32_t fromScene = scene_.settings.samplesPerPixel;
  values.samplesTarget = static_cast<int>(
      options_.samplesTarget ? *options_.samplesTarget : (fromScene ? fromScene : kDefaultSamples));
  values.bounces = static_cast<int>(scene_.settings.maxBounces);
  values.indirectClamp = scene_.settings.indirectClamp;
  values.lightSamples = static_cast<int>(options_.lightSamples.value_or(0));
  values.lightSplit = static_cast<int>(options_.lightSplit.value_or(0));
  values.areaLights = !scene_.areaLights.empty();
  values.adaptive = options_.adaptive || scene_.settings.adaptive;
  SamplerKind sampler =
      options_.sampler.value_or(samplerUnlessAsked(scene_.settings, values.adaptive));
  values.sampler = static_cast<int>(sampler);
  values.exposure = toneMappingFor(scene_).exposure * options_.exposure;
  values.lensScale = static_cast<float>(bounds.radius);
  showCameraLens();
}

void Viewer::showCameraLens() {
  settings().apertureRadius = camera_.camera().apertureRadius;
  settings().focusDistance = camera_.camera().focusDistance;
}

SamplerKind Viewer::samplerSetting() const {
  return static_cast<SamplerKind>(std::clamp(settings().sampler, 0, 2));
}

std::unique_ptr<ProgressiveRenderer> Viewer::makeRenderer(glm::uvec2 size) const {
  const OverlaySettings& values = settings();
  Scene scene = scene_;
  scene.settings.maxBounces = static_cast<uint32_t>(values.bounces);
  scene.settings.indirectClamp = std::max(values.indirectClamp, 0.0f);
  if (values.lightSamples > 0)
    setAreaLightSamples(scene, static_cast<uint32_t>(values.lightSamples));
  if (values.lightSplit > 0) scene.settings.lightSplit = static_cast<uint32_t>(values.lightSplit);
  scene.camera = camera_.camera();
  ProgressiveOptions options;
  options.width = size.x;
  options.height = size.y;
  options.samplesTotal = static_cast<uint32_t>(values.samplesTarget);
  options.seed = options_.seed;
  options.sampler = samplerSetting();
  options.shading = options_.shading;
  options.adaptive = values.adaptive;
  options.independentHalves = values.adaptive;  // the rounds' noise estimate
  options.oddSums = values.adaptive;
  // Encoded around the scene's own camera wherever this one has moved, as
  // the render command encodes a camera path's frames: the same image.
  options.frameOrigin = scene_.camera.position;
  // The exposure at this rebuild sets the bailout's steps, as `render
  // --exposure` does; moving the slider later only changes the display.
  options.displayMapping = displayMapping();
  return std::make_unique<ProgressiveRenderer>(*context_, *compiler_, scene, options);
}

void Viewer::useRenderer(std::unique_ptr<ProgressiveRenderer> renderer) {
  renderer_ = std::move(renderer);  // no frame in flight: the old one can go
  const std::vector<std::string>& warnings = renderer_->warnings();
  if (warnings != rendererWarnings_) {
    for (const std::string& warning : warnings)
      std::fprintf(stderr, "warning: %s\n", warning.c_str());
    rendererWarnings_ = warnings;
  }
  display_->setSource(renderer_->accumulation(), renderer_->width(), renderer_->height());
  restartAccumulation();
  rebuildFailed_ = false;
}

bool Viewer::rebuildRenderer(glm::uvec2 size) {
  preparing_.busy = true;
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
  accumulation_.restart(*renderer_, static_cast<uint32_t>(settings().samplesTarget),
                        settings().adaptive);
}

void Viewer::applyCameraChange() {
  if (!camera_.takeChanged()) return;
  const Camera& camera = camera_.camera();
  showCameraLens();
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
  glm::uvec2 wanted = resize_.wanted();
  if (wanted == current || rebuildFailed_) return;
  // Scripted runs have no one dragging the window border: no need to wait.
  if ((resize_.settled() || scripted()) && rebuildRenderer(wanted)) {
    std::printf("resize: rendering at %ux%u\n", wanted.x, wanted.y);
  }
}

void Viewer::recreateSwapchain() {
  glm::uvec2 size = window_->framebufferSize();
  if (size.x == 0 || size.y == 0) return;  // minimised: wait for a size
  swapchain_->recreate(toExtent(size));
  overlay_->onSwapchainRecreated(*swapchain_);
  swapchainStale_ = false;
  resize_.windowSized({swapchain_->extent().width, swapchain_->extent().height});
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
  return !scripted() && !accumulation_.accumulating() && !preparing_.reloadSavedAt && !quit_;
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
          (options_.frames > 0 && clock_.framesPresented() + 1 >= options_.frames);
  handleFileChanges();
  bool active = window_->takeActivity();
  if (idle() && !active && Clock::now() - clock_.lastPresentAt() < kIdleRedraw) return false;

  if (const PathStep* step = path_.next()) applyPathStep(*step);
  handleInput(window_->takeInput(overlay_->wantsMouse(), overlay_->wantsKeyboard()));
  applyOverlayActions(overlay_->build(overlayStats()));
  applyCameraChange();
  applyResize();
  if (quit_ && !options_.screenshot.empty()) preparing_.screenshots.push_back(options_.screenshot);
  return true;
}

void Viewer::waitForFrame() {
  if (!frameSync_->wait()) return;
  Clock::time_point now = Clock::now();
  double seconds = clock_.frameDone(submitted_.pixelSamples, now);
  // Only plain rendering frames say how much work fits into one.
  if (submitted_.rendered && !submitted_.busy) accumulation_.frameTook(seconds);

  if (submitted_.reloadSavedAt) {
    // The first frame drawn with reloaded shaders is finished and presented.
    std::printf("reload: presented %.0f ms after the save\n",
                1e3 * secondsBetween(*submitted_.reloadSavedAt, now));
  }
  // Nothing is in flight now: the replaced kernels can go.
  renderer_->releaseRetiredKernels();
  display_->releaseRetired();
  if (!submitted_.screenshots.empty()) {
    try {
      readback_->write(submitted_.screenshots);
      for (const auto& path : submitted_.screenshots) std::printf("screenshot: %s\n", path.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
    }
  }
  submitted_ = {};
}

bool Viewer::drawFrame() {
  glm::uvec2 size = window_->framebufferSize();
  VkExtent2D extent = swapchain_->extent();
  if (swapchainStale_ || size.x != extent.width || size.y != extent.height) recreateSwapchain();
  if (swapchainStale_ || size.x == 0 || size.y == 0) return false;

  uint32_t imageIndex = 0;
  VkResult acquired =
      vkAcquireNextImageKHR(context_->device(), swapchain_->handle(), UINT64_MAX,
                            frameSync_->imageAcquired(), VK_NULL_HANDLE, &imageIndex);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    swapchainStale_ = true;
    return false;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) vkCheck(acquired, "vkAcquireNextImageKHR");

  recordFrame(frameSync_->begin(), imageIndex);
  VkSemaphore renderFinished = swapchain_->renderFinished(imageIndex);
  frameSync_->submit(renderFinished);
  submitted_ = std::exchange(preparing_, {});

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
  clock_.presented();
  return true;
}

void Viewer::recordFrame(VkCommandBuffer commands, uint32_t imageIndex) {
  RowRange rendered = recordRenderBands(commands);
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

  if (!preparing_.screenshots.empty()) {
    if (swapchain_->readable()) {
      readback_->record(commands, image, extent, swapchain_->format());
    } else {
      std::fprintf(stderr, "error: this window's images cannot be read back; no screenshot\n");
      preparing_.screenshots.clear();
    }
  }
}

Viewer::RowRange Viewer::recordRenderBands(VkCommandBuffer commands) {
  Accumulation::FrameSamples frame = accumulation_.record(commands, displayMapping());
  if (frame.readBack) preparing_.busy = true;
  preparing_.pixelSamples = frame.pixelSamples;
  preparing_.rendered = frame.rows > 0;
  return {frame.firstRow, frame.rows};
}

void Viewer::logFrame() {
  uint32_t target = static_cast<uint32_t>(settings().samplesTarget);
  auto frames = static_cast<unsigned long long>(clock_.framesPresented());
  if ((submitted_.rendered || options_.verbose) && clock_.takeLogDue(options_.verbose)) {
    std::printf("frame %llu spp=%s/%u ms=%.1f msps=%.3f work=%llu\n", frames,
                accumulation_.samplesText().c_str(), target, clock_.frameMilliseconds(),
                clock_.samplesPerSecond() * 1e-6,
                static_cast<unsigned long long>(submitted_.pixelSamples));
  }
  if (std::optional<double> seconds = accumulation_.takeDoneSeconds()) {
    std::printf("done: spp=%s in %.2f s (frame %llu)\n", accumulation_.samplesText().c_str(),
                *seconds, frames);
  }
  std::fflush(stdout);
}

OverlayStats Viewer::overlayStats() const {
  OverlayStats stats;
  stats.samplesDone = accumulation_.samplesPerPixel();
  stats.adaptive = accumulation_.adaptive();
  stats.rmseEstimate = accumulation_.rmseEstimate();
  stats.samplesTarget = static_cast<uint32_t>(settings().samplesTarget);
  stats.samplesPerSecond = clock_.samplesPerSecond();
  stats.frameMilliseconds = clock_.frameMilliseconds();
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
