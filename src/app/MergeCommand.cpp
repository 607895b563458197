// raytracer merge PART.exr... OUTPUT: combines split renders (--samples).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "encode/Conventions.hpp"
#include "formats/SceneFile.hpp"
#include "imaging/Merge.hpp"
#include "io/AtomicFile.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"

namespace {

// .png and .ppm bytes as a render of `scenePath` writes them: its
// conventions' curve and quantization. The parts carry the exposure already.
rt::ToneMapping toneMappingOf(const std::string& scenePath, const std::string& conventions) {
  if (scenePath.empty()) return {};
  rt::Scene scene = rt::loadSceneFile(scenePath);
  rt::cli::applyConventionsOption(conventions, scene);
  rt::ToneMapping mapping = rt::toneMappingFor(scene);
  mapping.exposure = 1.0f;
  return mapping;
}

}  // namespace

int runMergeCommand(int argc, char** argv) {
  std::vector<std::string> paths;
  std::string scenePath;
  std::string conventions;
  CLI::App app{
      "Merges renders of disjoint sample ranges (raytracer --samples FROM:TO) into "
      "one image",
      "raytracer merge"};
  app.add_option("files", paths, "PART.exr ... OUTPUT (.exr keeps sample counts for re-merging)")
      ->required()
      ->expected(2, -1);
  app.add_option("--scene", scenePath,
                 "Write .png/.ppm bytes as a render of this scene does (its conventions' tone "
                 "curve and quantization; default: clamp and round)");
  rt::cli::addConventionsOption(app, conventions);
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    std::string output = paths.back();
    paths.pop_back();
    if (!rt::isSupportedImageExtension(output)) {
      throw rt::Error(rt::unsupportedOutputMessage(output));
    }
    rt::checkWritable(output);
    std::vector<rt::ImageF> parts;
    for (const std::string& path : paths) parts.push_back(rt::readExr(path));
    rt::ImageF merged = rt::mergeRenders(parts);
    rt::writeImage(output, merged, toneMappingOf(scenePath, conventions));
    std::fprintf(stderr, "merged %zu renders (%.0f samples per pixel) into %s\n", parts.size(),
                 double(merged.rgba[3]), output.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
