// The viewer's reactions between frames: file changes (hot reload), mouse
// and keys, camera-path steps and overlay edits. Everything here runs with no
// frame in flight, so it may rebuild or reconfigure the renderer.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "encode/FlatScene.hpp"
#include "formats/SceneFile.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/BatchIntersector.hpp"
#include "scene/SceneBounds.hpp"
#include "util/Error.hpp"
#include "viewer/DisplayPass.hpp"
#include "viewer/Swapchain.hpp"
#include "viewer/ThirdParty.hpp"
#include "viewer/Viewer.hpp"

namespace rt::viewer {
namespace {

// Mouse and keyboard sensitivity.
constexpr float kOrbitDegreesPerPixel = 0.3f;
constexpr float kFlyRadiiPerSecond = 0.5f;
constexpr float kFlyFastFactor = 4.0f;
constexpr double kMaxFlyStepSeconds = 0.1;  // a slow frame must not jump far

bool sameCamera(const Camera& a, const Camera& b) {
  return a.type == b.type && a.width == b.width && a.height == b.height &&
         a.fovYDegrees == b.fovYDegrees && a.position == b.position && a.forward == b.forward &&
         a.up == b.up && a.exposure == b.exposure && a.apertureRadius == b.apertureRadius &&
         a.focusDistance == b.focusDistance;
}

// Prints each line of a multi-line message with a prefix (log parsers and
// people both see which lines belong to it).
void printLines(FILE* stream, const std::string& prefix, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::fprintf(stream, "%s%s\n", prefix.c_str(), line.c_str());
  }
  std::fflush(stream);
}

// Positions keep their double precision (the shortest text that reads back the
// same) for pasting into a scene file.
std::string vectorText(const glm::dvec3& v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

}  // namespace

void Viewer::notice(const std::string& text) {
  overlay_->messages().notice = text;
  std::printf("%s\n", text.c_str());
  std::fflush(stdout);
}

void Viewer::reportShaderError(const std::string& what) {
  overlay_->messages().shaderError = what;
  printLines(stderr, "reload: error ", what);
}

void Viewer::handleFileChanges() {
  if (!reload_) return;
  HotReload::Due due = reload_->poll(Clock::now());
  if (due.shaders) reloadShaders();
  if (due.scene) reloadScene();
}

// Only with --watch (reload_ is set): after a save of a shader.
void Viewer::reloadShaders() {
  preparing_.busy = true;
  Clock::time_point start = Clock::now();
  std::string errors;
  bool traceReloaded = false;
  try {
    renderer_->reloadShaders();
    traceReloaded = true;
  } catch (const std::exception& e) {
    errors = e.what();
  }
  try {
    display_->reloadShader();
  } catch (const std::exception& e) {
    errors += (errors.empty() ? "" : "\n") + std::string(e.what());
  }
  double milliseconds = 1e3 * secondsSince(start);
  if (traceReloaded) {
    // New shading: what was accumulated so far no longer matches.
    renderer_->reset();
    restartAccumulation();
    preparing_.reloadSavedAt = reload_->shadersSavedAt();
  }
  if (!errors.empty()) {
    reportShaderError(errors);
    return;
  }
  overlay_->messages().shaderError.clear();
  overlay_->messages().shaders = fmt::format("reloaded in {:.0f} ms", milliseconds);
  rebuildFailed_ = false;  // a pending resize may try again
  std::printf("reload: ok %.0f ms\n", milliseconds);
  std::fflush(stdout);
  // A scene edit that could not be built with the broken shaders.
  if (reload_->sceneWaitsForShaders) reloadScene();
}

// Only with --watch: after a save of the scene file, or once shaders that
// build came after a scene edit that needed them.
void Viewer::reloadScene() {
  Scene fresh;
  try {
    fresh = loadViewedScene();
  } catch (const std::exception& e) {
    overlay_->messages().sceneError = e.what();
    std::fprintf(stderr, "scene: error %s\n", e.what());
    std::fflush(stderr);
    reload_->sceneWaitsForShaders = false;  // this version is broken itself
    return;
  }
  Scene previous = std::move(scene_);
  OrbitCamera previousCamera = camera_;
  OverlaySettings& values = settings();
  OverlaySettings previousSettings = values;
  // Keep the user's view unless the file's camera itself was edited.
  BoundingSphere bounds = boundingSphere(fresh);
  if (!sameCamera(previous.camera, fresh.camera)) {
    camera_.setHome(fresh.camera, bounds.center, bounds.radius);
    values.exposure = toneMappingFor(fresh).exposure * options_.exposure;
  }
  if (fresh.settings.maxBounces != previous.settings.maxBounces) {
    values.bounces = static_cast<int>(fresh.settings.maxBounces);
  }
  if (fresh.settings.indirectClamp != previous.settings.indirectClamp) {
    values.indirectClamp = fresh.settings.indirectClamp;
  }
  values.areaLights = !fresh.areaLights.empty();
  scene_ = std::move(fresh);
  if (!rebuildRenderer({renderer_->width(), renderer_->height()})) {
    scene_ = std::move(previous);
    camera_ = previousCamera;
    values = previousSettings;
    overlay_->messages().sceneError =
        "the scene loaded but the renderer could not be built (see shaders)";
    std::fprintf(stderr, "scene: error %s\n", overlay_->messages().sceneError.c_str());
    reload_->sceneWaitsForShaders = true;
    return;
  }
  reload_->sceneWaitsForShaders = false;
  values.lensScale = static_cast<float>(bounds.radius);
  showCameraLens();
  intersector_.reset();  // built again for the new geometry on the next focus click
  overlay_->messages().sceneError.clear();
  preparing_.reloadSavedAt = reload_->sceneSavedAt();
  for (const std::string& warning : scene_.warnings) {
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  }
  std::printf("scene: reloaded %s\n", options_.scenePath.c_str());
  std::fflush(stdout);
}

void Viewer::handleInput(const InputEvents& input) {
  float height = static_cast<float>(swapchain_->extent().height);
  if (input.orbitDrag != glm::dvec2(0.0)) {
    // Drag right: the scene turns right, so the camera moves left.
    camera_.orbit(-static_cast<float>(input.orbitDrag.x) * kOrbitDegreesPerPixel,
                  -static_cast<float>(input.orbitDrag.y) * kOrbitDegreesPerPixel);
  }
  if (input.panDrag != glm::dvec2(0.0)) {
    camera_.pan(glm::vec2(input.panDrag), height);
  }
  if (input.scroll != 0.0) {
    camera_.zoom(static_cast<float>(input.scroll));
  }
  for (const Click& click : input.clicks) {
    if (click.button == GLFW_MOUSE_BUTTON_LEFT && (click.mods & GLFW_MOD_CONTROL)) {
      focusAt(windowToRenderPixel(click.position));
    }
  }
  for (const KeyPress& key : input.keys) handleKey(key);
  bool ctrl = window_->keyHeld(GLFW_KEY_LEFT_CONTROL) || window_->keyHeld(GLFW_KEY_RIGHT_CONTROL);
  if (!overlay_->wantsKeyboard() && !ctrl) flyWithHeldKeys();
  lastInputAt_ = Clock::now();
}

void Viewer::handleKey(const KeyPress& key) {
  switch (key.key) {
    case GLFW_KEY_R: camera_.reset(); break;
    case GLFW_KEY_S:
      // Plain S flies backwards (WASD); Ctrl+S saves.
      if (key.mods & GLFW_MOD_CONTROL) saveImage({});
      break;
    case GLFW_KEY_H: overlay_->setVisible(!overlay_->visible()); break;
    case GLFW_KEY_P: printCamera(); break;
    case GLFW_KEY_ESCAPE: window_->requestClose(); break;
    default: break;
  }
}

void Viewer::flyWithHeldKeys() {
  double seconds = std::min(secondsSince(lastInputAt_), kMaxFlyStepSeconds);
  auto axis = [&](int positive, int negative) {
    return (window_->keyHeld(positive) ? 1.0f : 0.0f) - (window_->keyHeld(negative) ? 1.0f : 0.0f);
  };
  glm::vec3 direction{axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q),
                      axis(GLFW_KEY_W, GLFW_KEY_S)};
  if (direction == glm::vec3(0.0f)) return;
  bool fast = window_->keyHeld(GLFW_KEY_LEFT_SHIFT) || window_->keyHeld(GLFW_KEY_RIGHT_SHIFT);
  float speed = kFlyRadiiPerSecond * (fast ? kFlyFastFactor : 1.0f);
  camera_.fly(direction * speed * static_cast<float>(seconds));
}

void Viewer::applyPathStep(const PathStep& step) {
  using Kind = PathStep::Kind;
  const std::vector<float>& v = step.values;
  switch (step.kind) {
    case Kind::Orbit: camera_.orbit(v[0], v[1]); break;
    case Kind::Pan: camera_.pan({v[0], v[1]}, static_cast<float>(renderer_->height())); break;
    case Kind::Zoom: camera_.zoom(v[0]); break;
    case Kind::Fly: camera_.fly({v[0], v[1], v[2]}); break;
    case Kind::LookAt: camera_.lookAt({v[0], v[1], v[2]}, {v[3], v[4], v[5]}); break;
    case Kind::Lens: camera_.setLens(v[0], v[1]); break;
    case Kind::Focus: focusAt({v[0], v[1]}); break;
    case Kind::Reset: camera_.reset(); break;
    case Kind::Resize:
      window_->resize(static_cast<uint32_t>(std::max(v[0], 1.0f)),
                      static_cast<uint32_t>(std::max(v[1], 1.0f)));
      return;
    case Kind::Screenshot: preparing_.screenshots.push_back(step.file); return;
    case Kind::Save: saveImage(step.file); return;
    case Kind::Wait: return;
  }
}

void Viewer::applyOverlayActions(const OverlayActions& actions) {
  glm::uvec2 size{renderer_->width(), renderer_->height()};
  if (actions.bouncesChanged || actions.clampChanged || actions.lightSamplesChanged ||
      actions.lightSplitChanged || actions.samplerChanged || actions.adaptiveChanged) {
    rebuildRenderer(size);
  } else if (actions.targetChanged) {
    // The jittered sampler stratifies for the target count: a new target is
    // a new sample pattern. Random samples stay valid; just go on. Adaptive
    // rounds plan for their budget: a new one starts again.
    if (samplerSetting() == SamplerKind::Jittered || settings().adaptive) {
      rebuildRenderer(size);
    } else {
      accumulation_.setTarget(static_cast<uint32_t>(settings().samplesTarget));
    }
  }
  if (actions.lensChanged) {
    camera_.setLens(settings().apertureRadius, settings().focusDistance);
  }
  if (actions.resetCamera) {
    camera_.reset();
  }
  if (actions.save) saveImage({});
}

glm::dvec2 Viewer::windowToRenderPixel(glm::dvec2 framebufferPixel) const {
  glm::uvec2 renderSize{renderer_->width(), renderer_->height()};
  FitRect fit = fitInto(renderSize, swapchain_->extent());
  if (fit.size.x <= 0 || fit.size.y <= 0) return glm::dvec2(-1.0);
  return (framebufferPixel - glm::dvec2(fit.offset)) * glm::dvec2(renderSize) /
         glm::dvec2(fit.size);
}

void Viewer::focusAt(glm::dvec2 renderPixel) {
  glm::uvec2 size{renderer_->width(), renderer_->height()};
  if (renderPixel.x < 0.0 || renderPixel.y < 0.0 || renderPixel.x >= size.x ||
      renderPixel.y >= size.y) {
    return;
  }
  // The primary ray through the pixel, built exactly as shaders/camera.glsl.
  const Camera& camera = camera_.camera();
  gpu::GpuSceneInfo info{};
  fillCamera(camera, size.x, size.y, GpuFrame{}, info);
  glm::vec2 ndc = 2.0f * glm::vec2(renderPixel) / glm::vec2(size) - 1.0f;
  glm::vec2 screen = glm::vec2(ndc.x * info.aspect, -ndc.y) * info.tanHalfFovY;
  glm::vec3 direction =
      glm::normalize(info.cameraForward + screen.x * info.cameraRight + screen.y * info.cameraUp);
  try {
    if (!intersector_) {
      preparing_.busy = true;
      intersector_ = std::make_unique<BatchIntersector>(*context_, *compiler_, scene_);
    }
    std::vector<gpu::GpuHit> hits =
        intersector_->intersect(std::vector<WorldRay>{{camera.position, direction, 1e30f}});
    if (hits[0].t <= 0.0f) {
      notice("focus: no surface under the cursor");
      return;
    }
    // The focal plane is perpendicular to the view axis.
    float distance = hits[0].t * glm::dot(direction, info.cameraForward);
    camera_.setLens(camera.apertureRadius, distance);
    // Through a pinhole every distance looks the same: setLens does not
    // count that as a change, and the accumulation goes on.
    settings().focusDistance = distance;
    notice(fmt::format("focus: distance={:.4f}{}", distance,
                       camera.apertureRadius > 0.0f ? "" : " (set a lens radius to see it)"));
  } catch (const std::exception& e) {
    notice(fmt::format("focus: error {}", e.what()));
  }
}

void Viewer::saveImage(std::filesystem::path path) {
  preparing_.busy = true;
  if (path.empty()) {
    // <scene>-<N>.png in the save folder, never overwriting an earlier save.
    std::string stem = options_.scenePath.stem().string();
    for (int n = 1;; ++n) {
      path = options_.saveFolder / fmt::format("{}-{}.png", stem, n);
      if (!std::filesystem::exists(path)) break;
    }
  }
  try {
    writeImage(path, renderer_->resolve(), displayMapping());
    notice(fmt::format("saved: {} ({} spp)", path.string(), accumulation_.samplesText()));
  } catch (const std::exception& e) {
    notice(fmt::format("save: error {}", e.what()));
  }
}

void Viewer::printCamera() const {
  const Camera& camera = camera_.camera();
  std::printf("camera: \"position\": %s, \"lookAt\": %s, \"upVector\": %s, \"fov\": %.3f\n",
              vectorText(camera.position).c_str(), vectorText(camera_.pivot()).c_str(),
              vectorText(glm::dvec3(camera.up)).c_str(), camera.fovYDegrees);
  std::fflush(stdout);
}

}  // namespace rt::viewer
