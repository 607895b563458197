#include "support/TestSupport.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <random>
#include <tuple>

#include "formats/json/JsonSceneLoader.hpp"

namespace rt::test {

std::vector<gpu::GpuRay> raysTowardsOrigin(size_t count, uint32_t seed, float targetExtent) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<gpu::GpuRay> rays;
  while (rays.size() < count) {
    glm::vec3 from(unit(rng), unit(rng), unit(rng));
    if (glm::length(from) < 0.1f || glm::length(from) > 1.0f) continue;
    from = 6.0f * glm::normalize(from);
    glm::vec3 to = targetExtent * glm::vec3(unit(rng), unit(rng), unit(rng));
    rays.push_back({from, 0.0f, glm::normalize(to - from), 1e30f});
  }
  return rays;
}

std::optional<std::filesystem::path> sharedDir() {
  const char* fromEnvironment = std::getenv("RT_SHARED_DIR");
  std::filesystem::path dir = fromEnvironment ? fromEnvironment : RT_SHARED_DIR;
  if (std::filesystem::is_directory(dir / "scene-format")) return dir;
  return std::nullopt;
}

doctest::skip needsShared() { return doctest::skip(!sharedDir().has_value()); }

std::filesystem::path requireShared() {
  std::optional<std::filesystem::path> dir = sharedDir();
  REQUIRE_MESSAGE(dir.has_value(), "no shared folder (RT_SHARED_DIR or " RT_SHARED_DIR ")");
  return *dir;
}

doctest::skip needsRayQueries() {
  static const bool supported = [] {
    try {
      std::vector<DeviceDescription> devices = VulkanContext::listDevices();
      return std::any_of(devices.begin(), devices.end(),
                         [](const DeviceDescription& device) { return device.rayQueries; });
    } catch (const std::exception&) {
      return false;
    }
  }();
  return doctest::skip(!supported);
}

VulkanContext& gpu() {
  static std::unique_ptr<VulkanContext> context = [] {
    ContextOptions options;
    options.validation = true;
    options.rayQueries = RayQueries::IfSupported;
    return std::make_unique<VulkanContext>(options);
  }();
  return *context;
}

const ShaderCompiler& shaderCompiler() {
  static ShaderCompiler compiler(RT_SOURCE_SHADER_DIR, RT_TEST_SHADER_CACHE);
  return compiler;
}

TempDir::TempDir() {
  static int made = 0;
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  path_ = std::filesystem::temp_directory_path() /
          ("rt_test_" + std::to_string(stamp) + "_" + std::to_string(++made));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path TempDir::write(const std::filesystem::path& relative,
                                     const std::string& text) const {
  const std::filesystem::path file = path_ / relative;
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

std::filesystem::path scratchShaderDir(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "shaders" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy(RT_SOURCE_SHADER_DIR, dir, std::filesystem::copy_options::recursive);
  return dir;
}

void checkNoValidationMessages() {
  static uint32_t seen = 0;
  uint32_t now = gpu().validationMessageCount();
  CHECK_MESSAGE(now == seen, "Vulkan validation layer reported ", now - seen, " message(s)");
  seen = now;
}

Material diffuse(glm::vec3 color, float kd, float ks) {
  Material m;
  m.diffuseColor = color;
  m.kd = kd;
  m.ks = ks;
  m.specularExponent = 20;
  return m;
}

void addSphere(Scene& scene, Material material, glm::vec3 center, float radius) {
  scene.materials.push_back(material);
  Shape shape;
  shape.geometry = Sphere{WorldPoint(center), radius};
  shape.material = uint32_t(scene.materials.size() - 1);
  scene.shapes.push_back(std::move(shape));
}

ImageF render(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
  Renderer renderer(gpu(), shaderCompiler());
  ImageF image = renderer.render(scene, options, {}, stats);
  checkNoValidationMessages();
  return image;
}

std::filesystem::path projectScenePath(const std::string& name) {
  return std::filesystem::path(RT_SOURCE_SHADER_DIR) / ".." / "scenes" / name;
}

Scene projectScene(const std::string& name) { return loadJsonScene(projectScenePath(name)); }

RenderOptions studyRender(SamplerKind sampler, uint32_t samples, uint32_t seed, uint32_t width) {
  RenderOptions options;
  options.width = width;
  options.height = width * 3 / 4;
  options.sampler = sampler;
  options.samplesPerPixel = samples;
  options.seed = seed;
  return options;
}

const ImageF& studyTruth(const std::string& name, uint32_t width, uint32_t samples) {
  static std::map<std::tuple<std::string, uint32_t, uint32_t>, ImageF> truths;
  auto key = std::tuple{name, width, samples};
  auto found = truths.find(key);
  if (found == truths.end()) {
    RenderOptions options = studyRender(SamplerKind::Sobol, samples, 999, width);
    found = truths.emplace(key, render(projectScene(name), options)).first;
  }
  return found->second;
}

double psnr(const Image8& a, const Image8& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  double sum = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    double d = double(a.rgb[i]) - double(b.rgb[i]);
    sum += d * d;
  }
  double mse = sum / double(a.rgb.size());
  return mse == 0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

void savePng(const Image8& image, const std::string& name) {
  ImageF exact{image.width, image.height, {}};
  for (size_t i = 0; i < image.rgb.size(); i += 3) {
    for (int c = 0; c < 3; ++c) exact.rgba.push_back(image.rgb[i + c] / 255.0f);
    exact.rgba.push_back(1.0f);
  }
  std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
  writeImage(std::filesystem::path(RT_TEST_OUTPUT_DIR) / name, exact, {});
}

Image8 downscale(const Image8& image, uint32_t width, uint32_t height) {
  Image8 out{width, height, std::vector<uint8_t>(size_t(width) * height * 3)};
  for (uint32_t y = 0; y < height; ++y) {
    uint32_t y0 = y * image.height / height;
    uint32_t y1 = std::max(y0 + 1, (y + 1) * image.height / height);
    for (uint32_t x = 0; x < width; ++x) {
      uint32_t x0 = x * image.width / width;
      uint32_t x1 = std::max(x0 + 1, (x + 1) * image.width / width);
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (uint32_t sy = y0; sy < y1; ++sy) {
          for (uint32_t sx = x0; sx < x1; ++sx)
            sum += image.rgb[(size_t(sy) * image.width + sx) * 3 + c];
        }
        out.rgb[(size_t(y) * width + x) * 3 + c] =
            static_cast<uint8_t>(std::lround(sum / double((y1 - y0) * (x1 - x0))));
      }
    }
  }
  return out;
}

Scene frontStage(uint32_t width, uint32_t height, glm::vec3 light, float intensity) {
  Scene scene;
  scene.conventions = Conventions::Textbook;
  scene.camera.width = width;
  scene.camera.height = height;
  scene.camera.position = {0, 0, 5};
  scene.camera.forward = {0, 0, -1};
  scene.camera.fovYDegrees = 40;
  scene.backgroundColor = {0.1f, 0.2f, 0.3f};
  scene.pointLights.push_back({WorldPoint(light), glm::vec3(intensity), glm::vec3(intensity)});
  return scene;
}

}  // namespace rt::test
