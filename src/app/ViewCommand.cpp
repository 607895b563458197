// raytracer view SCENE [options]: the interactive viewer (src/viewer). This
// file only turns the command line into rt::viewer::ViewerOptions.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "io/AtomicFile.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"
#include "viewer/ViewerOptions.hpp"

namespace {

using rt::cli::kMaxSamples;

struct CommandLine {
  std::string scenePath;
  std::string size;
  std::string sampler;
  std::string shading;
  std::string conventions;
  std::string toneCurve;
  std::string device;
  bool noOverlay = false;
  bool noWatch = false;
  double frameMilliseconds = 75.0;
  rt::cli::ModeOptions modeOptions;
};

void finishOptions(const CommandLine& cli, rt::viewer::ViewerOptions& options) {
  options.scenePath = cli.scenePath;
  if (!cli.size.empty()) {
    rt::cli::Size size = rt::cli::parseSize(cli.size);
    options.width = size.width;
    options.height = size.height;
  }
  if (!cli.sampler.empty()) options.sampler = rt::cli::samplerNamed(cli.sampler, {});
  if (auto shading = rt::cli::shadingNamed(cli.shading)) options.shading = shading;
  if (!cli.conventions.empty()) options.conventions = rt::conventionsNamed(cli.conventions);
  options.toneCurve = rt::cli::toneCurveOption(cli.toneCurve);
  options.mode = rt::cli::renderModeNamed(cli.modeOptions.mode);
  options.bounces = cli.modeOptions.bounces;
  if (!cli.device.empty()) options.deviceIndex = rt::cli::parseDeviceIndex(cli.device);
  options.overlay = !cli.noOverlay;
  options.watch = !cli.noWatch;
  options.frameSeconds = cli.frameMilliseconds * 1e-3;
  if (!options.screenshot.empty() && !rt::is8BitImagePath(options.screenshot)) {
    throw rt::Error(fmt::format("--screenshot {}: must be a {} file", options.screenshot.string(),
                                rt::k8BitOutputFormats));
  }
  if (!options.screenshot.empty()) rt::checkWritable(options.screenshot);
  if (!std::filesystem::is_directory(options.saveFolder)) {
    throw rt::Error(fmt::format("--save-dir {}: no such folder", options.saveFolder.string()));
  }
}

}  // namespace

int runViewCommand(int argc, char** argv) {
  CommandLine cli;
  rt::viewer::ViewerOptions options;
  CLI::App app{
      "Interactive viewer: progressive rendering in a window, hot reload of shaders "
      "and the scene file.",
      "raytracer view"};
  app.add_option("scene", cli.scenePath, rt::cli::kSceneFileHelp)->required();
  app.add_option("--size", cli.size,
                 "Initial window size WIDTHxHEIGHT (default: the scene's); "
                 "the render always has the window's size");
  app.add_option("--max-spp", options.samplesTarget,
                 "Samples per pixel to accumulate, then stop (default: the scene's, else 16)")
      ->check(CLI::Range(1u, kMaxSamples));
  app.add_option("--spp-per-frame", options.samplesPerFrame,
                 "Fixed samples per pixel per frame over the whole image (default: row bands "
                 "sized for --frame-ms)")
      ->check(CLI::Range(1u, kMaxSamples));
  app.add_option("--frame-ms", cli.frameMilliseconds,
                 "Target frame time without --spp-per-frame (75)")
      ->check(CLI::Range(5.0, 2000.0));
  app.add_option("--frames", options.frames, "Exit after N frames (default: when closed)");
  app.add_option("--camera-path", options.cameraPath,
                 "Text file of camera steps, one per frame (see src/viewer/CameraPath.hpp)");
  app.add_option("--screenshot", options.screenshot,
                 std::string("Write the last presented frame (the swapchain image) to this ") +
                     rt::k8BitOutputFormats);
  app.add_option("--save-dir", options.saveFolder, "Folder for Ctrl+S saves (default: .)");
  app.add_flag("--no-overlay", cli.noOverlay, "Start with the overlay hidden (H toggles it)");
  app.add_flag("--no-watch", cli.noWatch, "Do not reload shaders or the scene on changes");
  app.add_option("--shader-dir", options.shaderDir,
                 "Folder with the GLSL shaders, watched for changes (default: built-in path)");
  app.add_flag("--validation", options.validation,
               "Enable the Vulkan validation layer; any message fails the run");
  app.add_option("--device", cli.device, "Number of the Vulkan device to use");
  app.add_option("--seed", options.seed, "Random seed (as the render command)");
  app.add_option("--sampler", cli.sampler,
                 "Sampler of every random dimension (default: the scene's, else jittered)")
      ->check(CLI::IsMember({"random", "jittered", "sobol"}));
  app.add_flag("--adaptive", options.adaptive,
               "Adaptive sampling, as the render command: --max-spp is the mean budget");
  app.add_option("--shading", cli.shading, "Shading model (as the render command)")
      ->check(CLI::IsMember({"standard", "coursework"}));
  rt::cli::addConventionsOption(app, cli.conventions);
  rt::cli::addModeOptions(app, cli.modeOptions);
  rt::cli::addToneCurveOption(app, cli.toneCurve);
  rt::cli::addLightSamplesOption(app, options.lightSamples);
  rt::cli::addLightSplitOption(app, options.lightSplit);
  app.add_option("--exposure", options.exposure, "Extra exposure factor")
      ->check(rt::cli::positiveFiniteNumber());
  app.add_flag("-v,--verbose", options.verbose, "Log every frame (default: about once a second)");
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    finishOptions(cli, options);
    return rt::viewer::runViewer(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
