// raytracer merge PART.exr... OUTPUT: combines split renders (--samples).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "imaging/Merge.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"

int runMergeCommand(int argc, char** argv) {
  std::vector<std::string> paths;
  CLI::App app{
      "Merges renders of disjoint sample ranges (raytracer --samples FROM:TO) into "
      "one image",
      "raytracer merge"};
  app.add_option("files", paths, "PART.exr ... OUTPUT (.exr keeps sample counts for re-merging)")
      ->required()
      ->expected(2, -1);
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    std::string output = paths.back();
    paths.pop_back();
    if (!rt::isSupportedImageExtension(output)) {
      throw rt::Error(output + ": unsupported output format (use .exr, .hdr, .png or .ppm)");
    }
    std::vector<rt::ImageF> parts;
    for (const std::string& path : paths) parts.push_back(rt::readExr(path));
    rt::ImageF merged = rt::mergeRenders(parts);
    rt::writeImage(output, merged, {});
    std::fprintf(stderr, "merged %zu renders (%.0f samples per pixel) into %s\n", parts.size(),
                 double(merged.rgba[3]), output.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
