// Every GPU struct of gpu_types.h as the shaders read it: the host uploads a
// record whose every 4-byte word holds a different value, a probe kernel
// (layout_probe.comp) loads it with the shaders' reader (loadMaterial,
// loadAreaLight, ...) and stores it back as a std430 struct. Equal words mean
// each field sits at the offset both sides assume: two fields of one type
// swapped in a reader, or a texel row read in the wrong order, fail here,
// which size asserts cannot see.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "encode/FlatScene.hpp"
#include "encode/SceneBuffers.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu_types.h"
#include "support/TestSupport.hpp"

using namespace rt;
using namespace rt::gpu;

namespace {

constexpr size_t kWordBytes = sizeof(uint32_t);

// Word i holds the bits of the float 1.5 + i: a distinct, normal float (no
// reader may flush or canonicalise it), kept bit for bit by the uint fields.
template <typename T>
T sentinel(uint32_t salt) {
  static_assert(sizeof(T) % kWordBytes == 0);
  T record{};
  for (size_t i = 0; i < sizeof(T) / kWordBytes; ++i) {
    float value = 1.5f + float(i) + 100.0f * float(salt);
    std::memcpy(reinterpret_cast<char*>(&record) + i * kWordBytes, &value, kWordBytes);
  }
  return record;
}

uint32_t wordAt(const void* record, size_t index) {
  uint32_t word = 0;
  std::memcpy(&word, static_cast<const char*>(record) + index * kWordBytes, kWordBytes);
  return word;
}

const ShaderCompiler& probeCompiler() {
  static const ShaderCompiler compiler = [] {
    std::filesystem::path dir = test::scratchShaderDir("layout-probe");
    std::filesystem::copy_file(
        std::filesystem::path(RT_SOURCE_SHADER_DIR) / ".." / "tests" / "gpu" / "layout_probe.comp",
        dir / "layout_probe.comp");
    return ShaderCompiler(dir, RT_TEST_SHADER_CACHE);
  }();
  return compiler;
}

// A scene of one sentinel record in every array, and sentinel constants.
struct ProbeScene {
  FlatScene flat;
  GpuFrameParams frame = sentinel<GpuFrameParams>(1);

  ProbeScene() {
    flat.info = sentinel<GpuSceneInfo>(2);
    flat.primitives = {sentinel<GpuPrimitive>(3)};
    flat.materials = {sentinel<GpuMaterial>(4)};
    flat.pointLights = {sentinel<GpuPointLight>(5)};
    flat.areaLights = {sentinel<GpuAreaLight>(6)};
    flat.emitters = {sentinel<GpuEmitter>(7)};
    flat.vertices = {sentinel<GpuVertex>(8)};
    flat.textureInfos = {sentinel<GpuTextureInfo>(9)};
  }
};

const ProbeScene& probeScene() {
  static const ProbeScene scene;
  return scene;
}

// What RT_PROBE_READ returned for struct `type`, as the host's T.
template <typename T>
T probe(const std::string& type, const std::string& read) {
  ShaderDefines defines = {
      {"RT_PROBE_TYPE", type},           {"RT_PROBE_READ", read},
      {"RT_FEATURE_AREA_LIGHTS", "1"},   {"RT_FEATURE_VERTICES", "1"},
      {"RT_FEATURE_TEXTURES", "1"},      {"RT_FEATURE_METAL_ROUGH_TEXTURES", "1"},
      {"RT_FEATURE_ALPHA_CUTOUTS", "1"}, {"RT_FEATURE_TRANSMISSION_TEXTURES", "1"}};
  std::vector<KernelBinding> bindings = SceneBuffers::bindings();
  bindings.push_back({RT_BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  ComputeKernel kernel(test::gpu(), probeCompiler().compile("layout_probe.comp", defines), bindings,
                       uint32_t(sizeof(GpuFrameParams)));
  SceneBuffers buffers(test::gpu(), probeScene().flat);
  buffers.bindTo(kernel);
  Buffer output(test::gpu(), sizeof(T), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  output.fillZero();
  kernel.bind(RT_BINDING_HITS, output);
  test::gpu().submitAndWait(
      [&](VkCommandBuffer commands) { kernel.recordDispatch(commands, &probeScene().frame, 1); });
  T result{};
  output.download(&result, sizeof(T));
  test::checkNoValidationMessages();
  return result;
}

// Every word but the padding (`pads`: byte offsets) came back unchanged.
template <typename T>
void checkRoundTrip(const T& uploaded, const T& probed, std::vector<size_t> pads = {}) {
  for (size_t i = 0; i < sizeof(T) / kWordBytes; ++i) {
    bool pad = false;
    for (size_t offset : pads) pad = pad || offset == i * kWordBytes;
    if (pad) continue;
    CAPTURE(i * kWordBytes);  // byte offset of the field that moved
    CHECK(wordAt(&probed, i) == wordAt(&uploaded, i));
  }
}

}  // namespace

TEST_SUITE("gpu layout") {
  TEST_CASE("GpuSceneInfo: every field where loadSceneInfo reads it") {
    checkRoundTrip(probeScene().flat.info, probe<GpuSceneInfo>("GpuSceneInfo", "sceneInfo"));
  }

  TEST_CASE("GpuFrameParams: every field where loadFrameParams reads it") {
    checkRoundTrip(probeScene().frame, probe<GpuFrameParams>("GpuFrameParams", "frame"),
                   {offsetof(GpuFrameParams, pad0)});
  }

  TEST_CASE("GpuPrimitive: every field where loadPrimitive reads it") {
    checkRoundTrip(probeScene().flat.primitives[0],
                   probe<GpuPrimitive>("GpuPrimitive", "loadPrimitive(0u)"));
  }

  TEST_CASE("GpuMaterial: every field where loadMaterial reads it") {
    checkRoundTrip(probeScene().flat.materials[0],
                   probe<GpuMaterial>("GpuMaterial", "loadMaterial(0u)"));
  }

  TEST_CASE("GpuPointLight: every field where loadPointLight reads it") {
    checkRoundTrip(probeScene().flat.pointLights[0],
                   probe<GpuPointLight>("GpuPointLight", "loadPointLight(0u)"));
  }

  TEST_CASE("GpuAreaLight and GpuEmitter: every field where lights.glsl reads it") {
    checkRoundTrip(probeScene().flat.areaLights[0],
                   probe<GpuAreaLight>("GpuAreaLight", "loadAreaLight(0u)"));
    checkRoundTrip(probeScene().flat.emitters[0],
                   probe<GpuEmitter>("GpuEmitter", "loadEmitter(0u)"));
    checkRoundTrip(probeScene().flat.emitters[0],
                   probe<GpuEmitter>("GpuEmitter", "emitterThroughCdfEnd(0u)"));
  }

  TEST_CASE(
      "GpuVertex and GpuTextureInfo: every field where surface.glsl and textures.glsl read it") {
    checkRoundTrip(probeScene().flat.vertices[0], probe<GpuVertex>("GpuVertex", "loadVertex(0u)"));
    checkRoundTrip(probeScene().flat.textureInfos[0],
                   probe<GpuTextureInfo>("GpuTextureInfo", "loadTextureInfo(0)"));
  }
}
