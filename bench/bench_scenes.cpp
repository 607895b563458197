// rt-bench: renders scene files and prints a table of throughput. Not a
// test: it asserts nothing and is run on demand (bench/run-official.sh).
//   rt-bench [--width W] [--height H] [--spp N] [--accel bvh,hardware]
//            [--scene-arrays texel,storage] SCENE.json...
// Each scene renders twice and the second render is timed: the first pays
// for the driver's compile of the kernel (or finds it in Mesa's cache).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "formats/json/JsonSceneLoader.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/Renderer.hpp"

namespace {

struct Row {
  std::string scene;
  std::string accel;
  rt::RenderStats stats;
  double samples = 0;
};

void printTable(const std::vector<Row>& rows, const std::string& device, uint32_t width,
                uint32_t height, uint32_t spp) {
  std::printf("device: %s; %ux%u, %u spp, jittered sampler\n\n", device.c_str(), width, height,
              spp);
  std::printf("| %-42s | %-14s | %-50s | %6s | %8s | %10s | %10s | %8s |\n", "scene", "accel",
              "features", "prims", "time s", "Msamples/s", "Mrays/s", "rays/spl");
  std::printf(
      "|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(44, '-').c_str(), std::string(16, '-').c_str(),
      std::string(52, '-').c_str(), std::string(8, '-').c_str(), std::string(10, '-').c_str(),
      std::string(12, '-').c_str(), std::string(12, '-').c_str(), std::string(10, '-').c_str());
  for (const Row& row : rows) {
    double seconds = row.stats.renderSeconds;
    double rays = double(row.stats.raysTraced);
    std::printf("| %-42s | %-14s | %-50s | %6u | %8.3f | %10.2f | %10.2f | %8.2f |\n",
                row.scene.c_str(), row.accel.c_str(), row.stats.features.summary().c_str(),
                row.stats.primitives, seconds, row.samples / seconds * 1e-6, rays / seconds * 1e-6,
                rays / row.samples);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes;
  uint32_t width = 800;
  uint32_t height = 800;
  uint32_t spp = 16;
  CLI::App app{"Throughput of the renderer on scene files (prints a table)", "rt-bench"};
  app.add_option("scenes", scenes, "Scene files")->required();
  app.add_option("--width", width, "Image width")->check(CLI::Range(1u, 16384u));
  app.add_option("--height", height, "Image height")->check(CLI::Range(1u, 16384u));
  app.add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1u, 1u << 20));
  std::vector<std::string> accels;
  app.add_option("--accel", accels,
                 "Acceleration structures to time: bvh, hardware (default: bvh, and hardware "
                 "where the device has ray queries)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"bvh", "hardware"}));
  std::vector<std::string> arrayKinds;
  app.add_option("--scene-arrays", arrayKinds,
                 "Ways of reading the scene to time: texel, storage (default: texel, the "
                 "renderer's default; named kinds are shown in the accel column)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"texel", "storage"}));
  CLI11_PARSE(app, argc, argv);
  if (arrayKinds.empty()) arrayKinds = {""};
  try {
    rt::ContextOptions contextOptions;
    contextOptions.rayQueries = rt::RayQueries::IfSupported;
    rt::VulkanContext context(contextOptions);
    if (accels.empty()) {
      accels = {"bvh"};
      if (context.rayQueriesEnabled()) accels.push_back("hardware");
    }
    rt::ShaderCompiler compiler(rt::ShaderCompiler::defaultShaderDir(),
                                rt::ShaderCompiler::defaultCacheDir());
    rt::Renderer renderer(context, compiler);
    std::vector<Row> rows;
    for (const std::string& path : scenes) {
      rt::Scene scene = rt::loadJsonScene(path);
      for (const std::string& accel : accels) {
        for (const std::string& arrays : arrayKinds) {
          rt::RenderOptions options;
          options.width = width;
          options.height = height;
          options.samplesPerPixel = spp;
          options.countRays = true;
          options.accel = accel == "hardware" ? rt::AccelKind::Hardware : rt::AccelKind::Bvh;
          options.sceneArrays =
              arrays == "storage" ? rt::SceneArrays::StorageBuffers : rt::SceneArrays::TexelBuffers;
          const std::string label = arrays.empty() ? accel : accel + " " + arrays;
          Row row{std::filesystem::path(path).parent_path().filename().string() + "/" +
                      std::filesystem::path(path).filename().string(),
                  label,
                  {},
                  double(width) * height * spp};
          renderer.render(scene, options, {}, &row.stats);  // compiles the kernel
          renderer.render(scene, options, {}, &row.stats);
          std::fprintf(stderr, "%s (%s): %.2f s\n", row.scene.c_str(), label.c_str(),
                       row.stats.renderSeconds);
          rows.push_back(row);
        }
      }
    }
    printTable(rows, context.description().summary(), width, height, spp);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
