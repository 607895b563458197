// The Dear ImGui overlay: statistics, render settings and messages (shader
// and scene errors), drawn by ImGui's Vulkan backend in the swapchain render
// pass on top of the blitted render.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>

namespace rt {
class VulkanContext;
}

namespace rt::viewer {

class Swapchain;
class Window;

struct OverlayStats {
  double samplesDone = 0;  // per pixel; the mean under adaptive sampling
  uint32_t samplesTarget = 0;
  bool adaptive = false;
  std::optional<double> rmseEstimate;  // adaptive sampling's, after its first round
  double samplesPerSecond = 0.0;
  double frameMilliseconds = 0.0;
  glm::uvec2 renderSize{0};
  std::string device;
  std::string features;
  std::string scene;
};

// Values the overlay shows and lets the user edit.
struct OverlaySettings {
  int sampler = 1;  // SamplerKind: 0 random, 1 jittered, 2 sobol
  int samplesTarget = 16;
  bool adaptive = false;  // adaptive sampling: samplesTarget is the mean budget
  int bounces = 4;
  float indirectClamp = 0.0f;  // firefly clamp, 0: off (RenderSettings::indirectClamp)
  // Every area light's shadow rays a hit; 0: each light's own (the scene's).
  // Shown only for scenes with area lights.
  int lightSamples = 0;
  // Replicas of a hit's area-light estimate (RenderSettings::lightSplit); 0:
  // the renderer's choice (four shadow rays a hit in adaptive renders).
  int lightSplit = 0;
  bool areaLights = false;
  float exposure = 1.0f;
  float apertureRadius = 0.0f;
  float focusDistance = 1.0f;
  float lensScale = 1.0f;  // scene radius: range of the lens sliders
};

struct OverlayMessages {
  std::string shaders;      // last reload, e.g. "reloaded in 850 ms"
  std::string shaderError;  // "file:line: error: message" lines
  std::string sceneError;
  std::string notice;  // e.g. "saved: out.png"
};

// What the user asked for this frame.
struct OverlayActions {
  bool samplerChanged = false;
  bool adaptiveChanged = false;
  bool targetChanged = false;
  bool bouncesChanged = false;
  bool clampChanged = false;
  bool lightSamplesChanged = false;
  bool lightSplitChanged = false;
  bool lensChanged = false;
  bool save = false;
  bool resetCamera = false;
};

class Overlay {
 public:
  Overlay(Window& window, VulkanContext& context, const Swapchain& swapchain);
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  void setVisible(bool visible) { visible_ = visible; }
  bool visible() const { return visible_; }
  // Whether the overlay uses the mouse or keyboard (then the camera must not).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

  // The values the user edits and the messages shown.
  OverlaySettings& settings() { return settings_; }
  const OverlaySettings& settings() const { return settings_; }
  OverlayMessages& messages() { return messages_; }

  // Builds this frame's UI (nothing when hidden) and returns the user's edits
  // (applied to settings()).
  OverlayActions build(const OverlayStats& stats);
  // Records the draw commands; inside the swapchain render pass.
  void record(VkCommandBuffer commands);

  void onSwapchainRecreated(const Swapchain& swapchain);

 private:
  void createDescriptorPool();
  void uploadFonts();
  void fitToDisplay();

  VulkanContext& context_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  bool visible_ = true;
  bool compact_ = false;  // the window was small at the last frame: the panel collapsed
  OverlaySettings settings_;
  OverlayMessages messages_;
};

}  // namespace rt::viewer
