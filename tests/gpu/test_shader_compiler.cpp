#include <doctest/doctest.h>

#include <fstream>

#include "encode/Conventions.hpp"
#include "encode/Features.hpp"
#include "encode/SceneBuffers.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu_types.h"
#include "noise_types.h"
#include "render/ProgressiveRenderer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

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

ShaderFeatures allFeatureFlags() {
  ShaderFeatures features;
  features.spheres = features.triangles = features.cylinders = true;
  features.reflection = features.refraction = features.thinLens = true;
  features.vertices = features.textures = true;
  features.whittedStackSize = 8;
  return features;
}

ShaderDefines allFeatures() { return allFeatureFlags().defines(); }

}  // namespace

TEST_SUITE("shader-compiler") {
  TEST_CASE("every .glsl file includes what it uses: each compiles on its own") {
    // A kernel of one #include, with no features and with every feature: a
    // file that relied on another being included first fails here.
    std::filesystem::path dir = test::scratchShaderDir("standalone");
    ShaderFeatures every;
    every.spheres = every.triangles = every.cylinders = every.meshes = true;
    every.looseTriangles = every.instanceTransforms = every.reflection = true;
    every.refraction = every.thinLens = every.vertices = every.textures = true;
    every.areaLights = every.diffuseBounces = every.laneVotes = true;
    every.vertexColors = every.normalMaps = every.glow = every.metalRoughTextures = true;
    every.tintedMirrors = every.tintedTransmission = every.thinWalls = every.transmissionTextures =
        every.alphaCutouts = every.textureSamplers = true;
    every.emitterKinds = 0xfu;
    every.whittedStackSize = 8;
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(RT_SOURCE_SHADER_DIR)) {
      if (entry.path().extension() != ".glsl") continue;
      const std::string name = entry.path().filename().string();
      std::ofstream(dir / "standalone.comp")
          << "#version 460\n#extension GL_GOOGLE_include_directive : require\n"
          << "layout(local_size_x = 1) in;\n#include \"" << name << "\"\nvoid main() {}\n";
      ShaderCompiler compiler(dir, "");
      for (const ShaderDefines& defines : {ShaderDefines{}, every.defines()}) {
        CAPTURE(name);
        CAPTURE(defines.size());
        CHECK_NOTHROW(compiler.compile("standalone.comp", defines));
      }
      ++files;
    }
    CHECK(files >= 14);
  }

  TEST_CASE("every kernel compiles with all features, and the device accepts it") {
    struct Entry {
      const char* file;
      ShaderFeatures features;
      std::vector<KernelBinding> bindings;
      uint32_t pushBytes;
    };
    // The render kernel also as CPU devices build it (the work queue and the
    // walk's vote on spilling its stack), and for a scene whose walks keep
    // their stack in registers.
    ShaderFeatures queued = allFeatureFlags();
    queued.workQueue = true;
    queued.laneVotes = true;
    ShaderFeatures shallow = allFeatureFlags();
    shallow.stackInRegisters = true;
    std::vector<KernelBinding> batch = SceneBuffers::bindings();
    batch.push_back({RT_BINDING_RAYS});
    batch.push_back({RT_BINDING_HITS});
    const std::vector<Entry> entries = {
        {"trace.comp", allFeatureFlags(), ProgressiveRenderer::kernelBindings(allFeatureFlags()),
         sizeof(gpu::GpuFrameParams)},
        {"trace.comp", queued, ProgressiveRenderer::kernelBindings(queued),
         sizeof(gpu::GpuFrameParams)},
        {"trace.comp", shallow, ProgressiveRenderer::kernelBindings(shallow),
         sizeof(gpu::GpuFrameParams)},
        {"intersect_batch.comp", allFeatureFlags(), batch, sizeof(gpu::GpuBatchParams)}};
    for (const Entry& entry : entries) {
      CAPTURE(entry.file);
      CAPTURE(entry.features.workQueue);
      CAPTURE(entry.features.stackInRegisters);
      std::vector<uint32_t> spirv =
          test::shaderCompiler().compile(entry.file, entry.features.defines());
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
    auto dir = test::scratchShaderDir("broken");
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

  TEST_CASE("a guarded file is inlined once, but again after a first inclusion under #if") {
    // A guarded file is inlined again only where an #if might have skipped
    // the copies before it, so every kernel's expanded source is smaller than
    // twice the shader folder. Before, the files that most others include were
    // inlined at every #include: 12 MB for the trace kernel, 73 times.
    ShaderCompiler compiler(RT_SOURCE_SHADER_DIR, "");
    size_t allFiles = 0;
    for (const auto& entry : std::filesystem::directory_iterator(RT_SOURCE_SHADER_DIR)) {
      allFiles += std::filesystem::file_size(entry.path());
    }
    for (const char* kernel : {"trace.comp", "intersect_batch.comp", "spawn_batch.comp",
                               "tile_noise.comp", "display.comp"}) {
      CAPTURE(kernel);
      CHECK(compiler.expandedSource(kernel, allFeatures()).size() < 2 * allFiles);
    }

    // A guarded file first included where an #if skips it must be inlined
    // again where it is included unconditionally.
    auto dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "shaders" / "guarded";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "helper.glsl") << "#ifndef HELPER_GLSL\n#define HELPER_GLSL\n"
                                          "float helper() { return 1.0; }\n#endif\n";
    std::ofstream(dir / "maybe.glsl") << "#ifndef MAYBE_GLSL\n#define MAYBE_GLSL\n"
                                         "#ifdef NEVER_DEFINED\n#include \"helper.glsl\"\n#endif\n"
                                         "#endif\n";
    std::ofstream(dir / "main.comp")
        << "#version 460\nlayout(local_size_x = 1) in;\n#include \"maybe.glsl\"\n"
           "#include \"helper.glsl\"\n#include \"helper.glsl\"\n"
           "layout(std430, binding = 0) buffer Out { float value; };\n"
           "void main() { value = helper(); }\n";
    ShaderCompiler scratch(dir, "");
    std::string source = scratch.expandedSource("main.comp", {});
    size_t first = source.find("float helper()");
    REQUIRE(first != std::string::npos);
    CHECK(source.find("float helper()", first + 1) != std::string::npos);  // under #if, and after
    CHECK(source.find("float helper()", source.find("float helper()", first + 1) + 1) ==
          std::string::npos);  // not a third time
    CHECK_NOTHROW(scratch.compile("main.comp", {}));
  }

  TEST_CASE("a shader reload rebuilds the noise kernel too, and a broken one keeps both") {
    // The viewer's hot reload (ProgressiveRenderer::reloadShaders) covers
    // tile_noise.comp: an edit that doubles each tile's variance sum shows in
    // the next measurement, a broken edit is reported with file:line.
    auto dir = test::scratchShaderDir("reload-noise");
    ShaderCompiler compiler(dir, "");
    Scene scene = test::projectScene("study-arealight.json");
    ProgressiveOptions options;
    options.width = 32;
    options.height = 24;
    options.samplesTotal = 8;
    options.sampler = SamplerKind::Sobol;
    options.independentHalves = true;
    ProgressiveRenderer job(test::gpu(), compiler, scene, options);
    job.addSamples(8);
    const ToneMapping mapping = toneMappingFor(scene);
    auto varianceSum = [&] {
      double sum = 0;
      for (const gpu::GpuTileNoise& tile : job.tileNoise(mapping)) sum += tile.varianceSum;
      return sum;
    };
    const double before = varianceSum();
    REQUIRE(before > 0);
    const std::string statement = "tile.varianceSum += squared * sum.w;";
    const int line = lineOf(dir / "tile_noise.comp", statement);
    REQUIRE(line > 0);
    replaceInFile(dir / "tile_noise.comp", statement, "tile.varianceSum += 2.0 * squared * sum.w;");
    job.reloadShaders();
    CHECK(varianceSum() == doctest::Approx(2 * before).epsilon(1e-5));
    replaceInFile(dir / "tile_noise.comp", "tile.varianceSum += 2.0 * squared * sum.w;",
                  "tile.varianceSum += undefinedThing;");
    try {
      job.reloadShaders();
      FAIL("the broken noise kernel compiled");
    } catch (const ShaderCompileError& e) {
      std::string message = e.what();
      CAPTURE(message);
      CHECK(message.find("tile_noise.comp:" + std::to_string(line) + ":") != std::string::npos);
    }
    CHECK(varianceSum() == doctest::Approx(2 * before).epsilon(1e-5));
    test::checkNoValidationMessages();
  }

  TEST_CASE("the cache returns the same SPIR-V and follows source edits") {
    auto dir = test::scratchShaderDir("cached");
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
