// Shared pieces of the test suite: where the shared data lives, one Vulkan
// context with the validation layer on, the shader compiler, and small
// scenes and rays several suites build on.
#pragma once

#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "gpu_types.h"
#include "io/Image.hpp"
#include "render/Renderer.hpp"
#include "scene/Scene.hpp"

namespace rt::test {

// The shared test data: $RT_SHARED_DIR, else ../shared beside the checkout
// (the build's RT_SHARED_DIR); nullopt when it is not there.
std::optional<std::filesystem::path> sharedDir();

// Decorator of every test case that reads ../shared: doctest skips it when
// the folder is missing (main() says so), so a clone without it reports
// those cases as skipped, never as passed.
doctest::skip needsShared();

// ../shared inside a test case decorated with needsShared(); fails the case
// when the folder is missing (it only runs then under --no-skip).
std::filesystem::path requireShared();

// Decorator of test cases that need ray queries (--accel hardware): skipped
// on devices without them (Mesa 22.3's lavapipe, older GPUs).
doctest::skip needsRayQueries();

// One context for the whole run, validation layer enabled, ray queries on
// where the device has them.
VulkanContext& gpu();
const ShaderCompiler& shaderCompiler();

// A scratch folder under the system temp dir, removed again at scope exit.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Writes `text` to path() / relative (making its folders) and returns the file.
  std::filesystem::path write(const std::filesystem::path& relative, const std::string& text) const;

 private:
  std::filesystem::path path_;
};

// A fresh copy of shaders/ under the test output folder, for kernels of the
// tests' own (probes) and for edits that must not touch the source tree.
std::filesystem::path scratchShaderDir(const std::string& name);

// Fails the current test if the validation layer said anything since the
// last call.
void checkNoValidationMessages();

// A Blinn-Phong material: diffuse `color` weighted kd, white highlights
// weighted ks (exponent 20), nothing reflected or refracted.
Material diffuse(glm::vec3 color, float kd = 1.0f, float ks = 0.0f);

// Adds `material` to the scene and a sphere made of it.
void addSphere(Scene& scene, Material material, glm::vec3 center = {0, 0, 0}, float radius = 1);

// Renders `scene` with a fresh Renderer on the test context; fails the
// current test on any validation message the render caused.
ImageF render(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

// A scene file of the project's scenes/ folder: its path, and loaded.
std::filesystem::path projectScenePath(const std::string& name);
Scene projectScene(const std::string& name);

// A small render of a study scene: width x (3/4 width).
RenderOptions studyRender(SamplerKind sampler, uint32_t samples, uint32_t seed, uint32_t width);
// The project scene `name` rendered so at `width` with `samples` Sobol
// samples of a seed no test renders with (999): a reference whose own error
// is far below the measured renders'. Rendered once per run.
const ImageF& studyTruth(const std::string& name, uint32_t width, uint32_t samples);

// Peak signal-to-noise ratio of two same-sized 8-bit images, in dB.
double psnr(const Image8& a, const Image8& b);

// Writes an 8-bit image into the test output folder, for looking at.
void savePng(const Image8& image, const std::string& name);

// Box-filter downscale to the given size (for comparing with small figures).
Image8 downscale(const Image8& image, uint32_t width, uint32_t height);

// Rays from random points of a sphere of radius 6 round the origin towards
// random points of a box of half-size `targetExtent` round the origin, so
// that many hit and many graze whatever a test scene holds there.
std::vector<gpu::GpuRay> raysTowardsOrigin(size_t count, uint32_t seed, float targetExtent);

// A family-B scene (no light falloff) with no shapes: the camera 5 units up
// +z looking at the origin (40 degrees), a blue-grey background and one
// white point light of `intensity` at `light`.
Scene frontStage(uint32_t width, uint32_t height, glm::vec3 light, float intensity);

}  // namespace rt::test
