#include "viewer/Overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "gpu/VulkanContext.hpp"
#include "scene/Limits.hpp"
#include "util/Error.hpp"
#include "viewer/Swapchain.hpp"
#include "viewer/ThirdParty.hpp"
#include "viewer/Window.hpp"

namespace rt::viewer {
namespace {

constexpr int kMaxSamplesTarget = 1 << 20;
// The sliders' ranges; the command line's --light-samples goes to kMaxLightSamples,
// --light-split to kMaxLightSplit.
constexpr int kMaxSliderLightSamples = 32;
constexpr int kMaxSliderLightSplit = 16;
const ImVec4 kErrorColor(1.0f, 0.45f, 0.4f, 1.0f);

void checkImGuiVulkanResult(VkResult result) {
  if (result < 0) std::fprintf(stderr, "error: ImGui Vulkan backend: VkResult %d\n", result);
}

void showStatistics(const OverlayStats& stats) {
  ImGui::Text("%s", stats.scene.c_str());
  ImGui::Text("%ux%u on %s", stats.renderSize.x, stats.renderSize.y, stats.device.c_str());
  // Wrapped: a textured, normal-mapped, glowing mesh lists more than a line holds.
  ImGui::TextWrapped("features: %s", stats.features.c_str());
  ImGui::Separator();
  if (stats.adaptive) {
    ImGui::Text("samples per pixel: %.1f / %u (mean)", stats.samplesDone, stats.samplesTarget);
    if (stats.rmseEstimate) ImGui::Text("estimated RMSE: %.5f", *stats.rmseEstimate);
  } else {
    ImGui::Text("samples per pixel: %.0f / %u", stats.samplesDone, stats.samplesTarget);
  }
  ImGui::Text("samples/s: %.2f M", stats.samplesPerSecond * 1e-6);
  ImGui::Text("frame time: %.1f ms", stats.frameMilliseconds);
}

void editRenderSettings(OverlaySettings& settings, OverlayActions& actions) {
  ImGui::Separator();
  // In SamplerKind order.
  const char* samplers[] = {"random", "jittered", "sobol"};
  actions.samplerChanged = ImGui::Combo("sampler", &settings.sampler, samplers, 3);
  actions.adaptiveChanged = ImGui::Checkbox("adaptive sampling", &settings.adaptive);
  bool stepped = ImGui::InputInt("target spp", &settings.samplesTarget, 1, 16,
                                 ImGuiInputTextFlags_EnterReturnsTrue);
  settings.samplesTarget = std::clamp(settings.samplesTarget, 1, kMaxSamplesTarget);
  actions.targetChanged = stepped || ImGui::IsItemDeactivatedAfterEdit();
  // A new bounce count rebuilds the renderer: apply it when the drag ends.
  ImGui::SliderInt("bounces", &settings.bounces, 0, static_cast<int>(kMaxBounces));
  actions.bouncesChanged = ImGui::IsItemDeactivatedAfterEdit();
  // The clamp is a scene constant: it also applies when the drag ends.
  ImGui::SliderFloat("clamp indirect", &settings.indirectClamp, 0.0f, 100.0f,
                     settings.indirectClamp > 0.0f ? "%.3f" : "off", ImGuiSliderFlags_Logarithmic);
  actions.clampChanged = ImGui::IsItemDeactivatedAfterEdit();
  if (settings.areaLights) {
    // A new count rebuilds the renderer too.
    ImGui::SliderInt("light samples", &settings.lightSamples, 0, kMaxSliderLightSamples,
                     settings.lightSamples > 0 ? "%d" : "scene's");
    settings.lightSamples =
        std::clamp(settings.lightSamples, 0, static_cast<int>(kMaxLightSamples));
    actions.lightSamplesChanged = ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderInt("light split", &settings.lightSplit, 0, kMaxSliderLightSplit,
                     settings.lightSplit > 0 ? "%d" : "auto");
    settings.lightSplit = std::clamp(settings.lightSplit, 0, static_cast<int>(kMaxLightSplit));
    actions.lightSplitChanged = ImGui::IsItemDeactivatedAfterEdit();
  }
  ImGui::SliderFloat("exposure", &settings.exposure, 0.01f, 100.0f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);
}

void editLens(OverlaySettings& settings, OverlayActions& actions) {
  ImGui::Separator();
  // The scene's radius, however small: scenes may be 1e-4 across.
  float scale = settings.lensScale > 0.0f ? settings.lensScale : 1.0f;
  bool radius = ImGui::SliderFloat("lens radius", &settings.apertureRadius, 0.0f, 0.2f * scale,
                                   "%.4f", ImGuiSliderFlags_Logarithmic);
  bool focus = ImGui::SliderFloat("focus distance", &settings.focusDistance, 1e-3f * scale,
                                  10.0f * scale, "%.3f", ImGuiSliderFlags_Logarithmic);
  actions.lensChanged = radius || focus;
  ImGui::TextDisabled("Ctrl+click: focus on the surface under the cursor");
}

void showMessages(const OverlayMessages& messages) {
  if (!messages.shaders.empty()) ImGui::Text("shaders: %s", messages.shaders.c_str());
  if (!messages.shaderError.empty()) {
    ImGui::TextColored(kErrorColor, "shader error (last good shaders keep rendering):");
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", messages.shaderError.c_str());
    ImGui::PopStyleColor();
  }
  if (!messages.sceneError.empty()) {
    ImGui::TextColored(kErrorColor, "scene error (last good scene kept):");
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", messages.sceneError.c_str());
    ImGui::PopStyleColor();
  }
  if (!messages.notice.empty()) ImGui::TextWrapped("%s", messages.notice.c_str());
}

}  // namespace

Overlay::Overlay(Window& window, VulkanContext& context, const Swapchain& swapchain)
    : context_(context) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working folder
  ImGui::StyleColorsDark();
  createDescriptorPool();
  // Installs ImGui's GLFW callbacks, which chain to the window's own.
  ImGui_ImplGlfw_InitForVulkan(window.handle(), true);

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context.instance();
  info.PhysicalDevice = context.physicalDevice();
  info.Device = context.device();
  info.QueueFamily = context.queueFamily();
  info.Queue = context.queue();
  info.DescriptorPool = pool_;
  info.Subpass = 0;
  info.MinImageCount = swapchain.minImageCount();
  info.ImageCount = std::max(swapchain.imageCount(), swapchain.minImageCount());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImGuiVulkanResult;
  ImGui_ImplVulkan_Init(&info, swapchain.renderPass());
  uploadFonts();
}

Overlay::~Overlay() {
  vkDeviceWaitIdle(context_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void Overlay::createDescriptorPool() {
  // ImGui needs one combined image sampler (the font atlas).
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.maxSets = 4;
  info.poolSizeCount = 1;
  info.pPoolSizes = &size;
  vkCheck(vkCreateDescriptorPool(context_.device(), &info, nullptr, &pool_),
          "vkCreateDescriptorPool");
}

void Overlay::uploadFonts() {
  context_.submitAndWait(
      [](VkCommandBuffer commands) { ImGui_ImplVulkan_CreateFontsTexture(commands); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

bool Overlay::wantsMouse() const { return visible_ && ImGui::GetIO().WantCaptureMouse; }

bool Overlay::wantsKeyboard() const { return visible_ && ImGui::GetIO().WantCaptureKeyboard; }

// In a small window the panel would hide the image: it collapses to its
// title bar whenever the window becomes small (a click opens it), and open
// it never takes more than part of the window (the rest scrolls).
void Overlay::fitToDisplay() {
  constexpr float kCompactWidth = 640.0f;
  constexpr float kCompactHeight = 480.0f;
  constexpr float kLargestWidthShare = 0.6f;
  constexpr float kLargestHeightShare = 0.8f;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const bool compact = display.x < kCompactWidth || display.y < kCompactHeight;
  if (compact != compact_) {
    ImGui::SetNextWindowCollapsed(compact, ImGuiCond_Always);
    compact_ = compact;
  }
  ImGui::SetNextWindowSizeConstraints(
      ImVec2(0.0f, 0.0f), ImVec2(display.x * kLargestWidthShare, display.y * kLargestHeightShare));
}

OverlayActions Overlay::build(const OverlayStats& stats) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  OverlayActions actions;
  if (visible_) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.8f);
    fitToDisplay();
    ImGui::Begin("raytracer", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(ImGui::GetFontSize() * 10.0f);
    showStatistics(stats);
    editRenderSettings(settings_, actions);
    editLens(settings_, actions);
    ImGui::Separator();
    actions.save = ImGui::Button("save image (Ctrl+S)");
    ImGui::SameLine();
    actions.resetCamera = ImGui::Button("reset camera (R)");
    showMessages(messages_);
    ImGui::TextDisabled("drag: orbit, right/middle drag: pan, wheel: zoom,");
    ImGui::TextDisabled("WASD/QE: fly (Shift: faster), H: hide, P: print camera");
    ImGui::PopItemWidth();
    ImGui::End();
  }
  ImGui::Render();
  return actions;
}

void Overlay::record(VkCommandBuffer commands) {
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), commands);
}

void Overlay::onSwapchainRecreated(const Swapchain& swapchain) {
  ImGui_ImplVulkan_SetMinImageCount(swapchain.minImageCount());
}

}  // namespace rt::viewer
