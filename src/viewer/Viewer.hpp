// The interactive viewer: a window showing a ProgressiveRenderer's
// accumulation while it grows, with camera controls, an ImGui overlay and hot
// reload of shaders and the scene file.
//
// Frame loop (one frame in flight): wait for the previous frame's fence; with
// nothing on the GPU, apply what changed (file reloads, camera moves, edited
// settings, window size); then record one command buffer: the render bands
// the Accumulation chose, the display pass (tone map the rows that changed,
// copy them into an RGBA8 image, blit that into the swapchain image), the
// overlay render pass and, when asked, a copy of the swapchain image for a
// screenshot; submit and present. The render always has the window's size:
// a resize rebuilds the renderer once the size held for a moment, and until
// then the old image is shown scaled.
#pragma once

#include <vulkan/vulkan.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/ProgressiveRenderer.hpp"
#include "scene/Scene.hpp"
#include "util/Clock.hpp"
#include "viewer/Accumulation.hpp"
#include "viewer/CameraPath.hpp"
#include "viewer/FrameClock.hpp"
#include "viewer/HotReload.hpp"
#include "viewer/OrbitCamera.hpp"
#include "viewer/Overlay.hpp"
#include "viewer/PendingResize.hpp"
#include "viewer/ViewerOptions.hpp"
#include "viewer/Window.hpp"

namespace rt {
class BatchIntersector;
class ShaderCompiler;
class VulkanContext;
}  // namespace rt

namespace rt::viewer {

class DisplayPass;
class FrameSync;
class Swapchain;
class SwapchainReadback;

// What a frame carries from its preparation until the GPU finished it.
struct FrameRecord {
  bool busy = false;      // heavy host work (a rebuild, a read-back): its time says nothing
  bool rendered = false;  // it added samples
  uint64_t pixelSamples = 0;
  std::vector<std::filesystem::path> screenshots;
  // When the file behind a successful reload was saved, for the first frame
  // drawn with the new shaders or scene.
  std::optional<SteadyClock::time_point> reloadSavedAt;
};

class Viewer {
 public:
  explicit Viewer(const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  int run();

 private:
  using Clock = SteadyClock;

  // Setup.
  void initialiseSettings();
  OverlaySettings& settings() { return overlay_->settings(); }
  const OverlaySettings& settings() const { return overlay_->settings(); }
  void showCameraLens();  // the camera's lens radius and focus into the overlay's sliders

  // The renderer (all only between frames).
  std::unique_ptr<ProgressiveRenderer> makeRenderer(glm::uvec2 size) const;  // throws
  void useRenderer(std::unique_ptr<ProgressiveRenderer> renderer);
  bool rebuildRenderer(glm::uvec2 size);  // false: error reported, old renderer kept
  void restartAccumulation();
  void applyCameraChange();
  void applyResize();
  SamplerKind samplerSetting() const;

  // Between frames: results of the last frame, reloads, input.
  void waitForFrame();
  void handleFileChanges();
  void reloadShaders();
  void reloadScene();
  // The scene file as loaded, with the --conventions override applied.
  Scene loadViewedScene() const;
  // The scene's tone mapping with the overlay's exposure (window and saves).
  ToneMapping displayMapping() const;
  void handleInput(const InputEvents& input);
  void handleKey(const KeyPress& key);
  void flyWithHeldKeys();
  void applyPathStep(const PathStep& step);
  void applyOverlayActions(const OverlayActions& actions);
  void focusAt(glm::dvec2 renderPixel);
  glm::dvec2 windowToRenderPixel(glm::dvec2 framebufferPixel) const;
  void saveImage(std::filesystem::path path);
  void printCamera() const;
  void notice(const std::string& text);
  void reportShaderError(const std::string& what);

  // The frame.
  bool scripted() const;  // --frames or a camera path: no waiting for people
  bool idle() const;
  bool prepareFrame();  // false: nothing to draw this time
  bool drawFrame();
  void recordFrame(VkCommandBuffer commands, uint32_t imageIndex);
  struct RowRange {
    uint32_t first = 0;
    uint32_t count = 0;
  };
  RowRange recordRenderBands(VkCommandBuffer commands);
  void recreateSwapchain();
  void logFrame();
  OverlayStats overlayStats() const;

  ViewerOptions options_;
  Scene scene_;  // the last scene file that loaded and built
  std::unique_ptr<Window> window_;
  std::unique_ptr<VulkanContext> context_;
  std::unique_ptr<ShaderCompiler> compiler_;
  std::unique_ptr<Swapchain> swapchain_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<Overlay> overlay_;
  std::unique_ptr<ProgressiveRenderer> renderer_;
  // The renderer's warnings last printed: renderers rebuilt for a moved
  // camera repeat them, and they are printed again only when they change.
  std::vector<std::string> rendererWarnings_;
  std::unique_ptr<BatchIntersector> intersector_;  // built on the first focus click
  std::unique_ptr<SwapchainReadback> readback_;
  std::unique_ptr<FrameSync> frameSync_;  // the one frame in flight
  std::unique_ptr<HotReload> reload_;     // with --watch
  bool swapchainStale_ = false;

  Accumulation accumulation_;
  OrbitCamera camera_;
  CameraPathPlayer path_;
  PendingResize resize_;
  bool rebuildFailed_ = false;  // do not retry a rebuild until the shaders change

  FrameClock clock_;
  FrameRecord preparing_;  // the frame being prepared
  FrameRecord submitted_;  // the frame in flight
  Clock::time_point lastInputAt_ = Clock::now();
  bool quit_ = false;
};

}  // namespace rt::viewer
