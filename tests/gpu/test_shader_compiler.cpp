#include <doctest/doctest.h>

#include <fstream>

#include "encode/Features.hpp"
#include "encode/SceneBuffers.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu_types.h"
#include "render/ProgressiveRenderer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

std::filesystem::path scratchShaderDir(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "shaders" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy(RT_SOURCE_SHADER_DIR, dir, std::filesystem::copy_options::recursive);
  return dir;
}

int lineOf(const std::filesystem::path& file, const std::string& needle) {
  std::ifstream in(file);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find(needle) != std::string::npos) return number;
  }
  return -1;
}

void replaceInFile(const std::filesystem::path& file, const std::string& from,
                   const std::string& to) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(file) << text;
}

ShaderDefines allFeatures() {
  ShaderFeatures features;
  features.spheres = features.triangles = features.cylinders = true;
  features.reflection = features.refraction = features.thinLens = true;
  features.vertices = features.textures = true;
  features.whittedStackSize = 8;
  return features.defines();
}

}  // namespace

TEST_SUITE("shader-compiler") {
  TEST_CASE("every kernel compiles with all features, and the device accepts it") {
    struct Entry {
      const char* file;
      std::vector<KernelBinding> bindings;
      uint32_t pushBytes;
    };
    std::vector<KernelBinding> render = ProgressiveRenderer::kernelBindings(false);
    std::vector<KernelBinding> batch = SceneBuffers::bindings();
    batch.push_back({RT_BINDING_RAYS});
    batch.push_back({RT_BINDING_HITS});
    const std::vector<Entry> entries = {
        {"trace.comp", render, sizeof(gpu::GpuFrameParams)},
        {"intersect_batch.comp", batch, sizeof(gpu::GpuBatchParams)}};
    for (const Entry& entry : entries) {
      CAPTURE(entry.file);
      std::vector<uint32_t> spirv = test::shaderCompiler().compile(entry.file, allFeatures());
      REQUIRE(spirv.size() > 5);
      CHECK(spirv[0] == 0x07230203u);
      ComputeKernel kernel(test::gpu(), spirv, entry.bindings, entry.pushBytes);
    }
    test::checkNoValidationMessages();
  }

  TEST_CASE("feature defines change the code: no refraction means less code") {
    ShaderFeatures minimal;
    minimal.spheres = true;
    ShaderCompiler compiler(RT_SOURCE_SHADER_DIR, "");
    auto small = compiler.compile("trace.comp", minimal.defines());
    auto large = compiler.compile("trace.comp", allFeatures());
    CHECK(small.size() < large.size());
  }

  TEST_CASE("a compile error names the included file and its line") {
    auto dir = scratchShaderDir("broken");
    const std::string statement = "float attenuation = sceneInfo.lightScale;";
    int line = lineOf(dir / "shading.glsl", statement);
    REQUIRE(line > 0);
    replaceInFile(dir / "shading.glsl", statement,
                  "float attenuation = sceneInfo.lightScale + undefinedThing;");
    ShaderCompiler compiler(dir, "");
    try {
      compiler.compile("trace.comp", allFeatures());
      FAIL("the broken shader compiled");
    } catch (const ShaderCompileError& e) {
      std::string message = e.what();
      CAPTURE(message);
      CHECK(message.find("shading.glsl:" + std::to_string(line) + ":") != std::string::npos);
      CHECK(message.find("undefinedThing") != std::string::npos);
    }
  }

  TEST_CASE("the cache returns the same SPIR-V and follows source edits") {
    auto dir = scratchShaderDir("cached");
    auto cache = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "shaders" / "cache";
    std::filesystem::remove_all(cache);
    ShaderCompiler compiler(dir, cache);
    auto first = compiler.compile("intersect_batch.comp", allFeatures());
    CHECK(std::distance(std::filesystem::directory_iterator(cache), {}) == 1);
    CHECK(compiler.compile("intersect_batch.comp", allFeatures()) == first);
    replaceInFile(dir / "intersect.glsl", "float det = u + v + w;",
                  "float det = u + v + w;\n  det += 0.0;");
    compiler.compile("intersect_batch.comp", allFeatures());
    CHECK(std::distance(std::filesystem::directory_iterator(cache), {}) == 2);
  }
}
