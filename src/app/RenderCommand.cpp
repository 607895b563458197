// raytracer SCENE OUTPUT [options]: the offline render command. A thin
// client of the renderer library: parse arguments, load, render, write.
#include <fmt/format.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "app/PathFrames.hpp"
#include "app/Progress.hpp"
#include "encode/Conventions.hpp"
#include "formats/SceneFile.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "imaging/SampleMaps.hpp"
#include "io/AtomicFile.hpp"
#include "io/Image.hpp"
#include "render/Renderer.hpp"
#include "util/Clock.hpp"
#include "util/Error.hpp"
#include "viewer/CameraPath.hpp"

namespace {

constexpr uint32_t kDefaultSamples = 16;
using rt::cli::kMaxSamples;

struct CommandLine {
  std::string scenePath;
  bool strict = false;
  std::string outputPath;
  std::optional<uint32_t> samples;
  std::string size;
  uint32_t seed = 0;
  std::string sampler;
  std::string shading;
  std::string conventions;
  std::string accel;
  std::string sceneArrays;
  std::string walks;
  std::string device;
  std::string shaderDir;
  std::optional<float> exposure;
  std::string toneCurve;
  std::optional<float> indirectClamp;
  std::optional<float> roulette;
  std::optional<float> bailout;
  std::optional<uint32_t> lightSamples;
  rt::cli::ModeOptions modeOptions;
  std::optional<uint32_t> lightSplit;
  std::string sampleRange;
  std::string region;
  std::string cameraPath;
  std::optional<uint32_t> frame;
  bool frameCount = false;
  std::optional<double> timeBudget;
  std::optional<double> targetRmse;
  bool estimateRmse = false;
  bool adaptive = false;
  std::string sampleMapPath;
  std::string errorMapPath;
  bool offscreen = true;
  bool validation = false;
  bool quiet = false;
};

// --samples FROM:TO: sample indices [FROM, TO) of a --spp render.
void parseSampleRange(const std::string& text, rt::RenderOptions& options) {
  static const std::regex pattern(R"((\d{1,9}):(\d{1,9}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw rt::Error(fmt::format("--samples {}: expected FROM:TO, e.g. 0:64", text));
  }
  uint32_t first = static_cast<uint32_t>(std::stoul(match[1].str()));
  uint32_t end = static_cast<uint32_t>(std::stoul(match[2].str()));
  if (first >= end || end > options.samplesPerPixel) {
    throw rt::Error(fmt::format("--samples {}: need FROM < TO <= the render's {} samples (--spp)",
                                text, options.samplesPerPixel));
  }
  options.firstSample = first;
  options.endSample = end;
}

// SIGINT/SIGTERM end the render after the dispatch in flight; what has
// accumulated is still written (atomically) with its sample count.
std::atomic<bool> interrupted{false};

void onInterrupt(int) { interrupted.store(true); }

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void listDevices() {
  auto devices = rt::VulkanContext::listDevices();
  for (const auto& d : devices) {
    std::printf("%u: %s (%s, Vulkan %u.%u, driver %s%s)\n", d.index, d.name.c_str(),
                d.typeName.c_str(), VK_API_VERSION_MAJOR(d.apiVersion),
                VK_API_VERSION_MINOR(d.apiVersion), d.driver.c_str(),
                d.rayQueries ? ", ray queries" : "");
  }
  if (devices.empty()) std::printf("no Vulkan devices\n");
}

rt::ContextOptions contextOptions(const CommandLine& cli) {
  rt::ContextOptions options;
  options.validation = cli.validation;
  if (cli.accel == "hardware") options.rayQueries = rt::RayQueries::Required;
  if (!cli.device.empty()) options.deviceIndex = rt::cli::parseDeviceIndex(cli.device);
  return options;
}

// Adaptive decisions depend on every pixel's samples so far, so pieces of an
// adaptive render would each decide differently and not merge into it.
void refuseSplitAdaptive(const CommandLine& cli, const rt::RenderOptions& options) {
  if (!options.adaptive) return;
  const char* why =
      " cannot be combined with adaptive sampling (--adaptive or the scene's "
      "\"adaptive\"): its decisions depend on the whole render's samples, so the "
      "pieces would not merge into one render";
  if (!cli.sampleRange.empty())
    throw rt::Error(fmt::format("--samples {}{}", cli.sampleRange, why));
  if (!cli.region.empty()) throw rt::Error(fmt::format("--region {}{}", cli.region, why));
}

// Checked before rendering, so that a bad option leaves no output file.
void checkMapOptions(const CommandLine& cli, const rt::RenderOptions& options) {
  for (const std::string& path : {cli.sampleMapPath, cli.errorMapPath}) {
    if (!path.empty() && !rt::is8BitImagePath(path)) {
      throw rt::Error(
          fmt::format("{}: a sample or error map is written as {}", path, rt::k8BitOutputFormats));
    }
  }
  if (!cli.errorMapPath.empty() && !options.estimateError && !options.adaptive) {
    throw rt::Error(
        fmt::format("--error-map {}: no error estimate to draw (add --adaptive, "
                    "--estimate-rmse or --target-rmse)",
                    cli.errorMapPath));
  }
}

// No --spp: a time budget or a target alone ends the render, whose sample
// count is not known in advance.
bool countOpen(const CommandLine& cli) {
  return (cli.targetRmse || cli.timeBudget) && !cli.samples;
}

rt::RenderOptions renderOptions(const CommandLine& cli, const rt::Scene& scene) {
  rt::RenderOptions options;
  if (!cli.size.empty()) {
    rt::cli::Size size = rt::cli::parseSize(cli.size);
    options.width = size.width;
    options.height = size.height;
  }
  uint32_t fromScene = scene.settings.samplesPerPixel;
  options.samplesPerPixel = cli.samples ? *cli.samples : (fromScene ? fromScene : kDefaultSamples);
  options.adaptive = cli.adaptive || scene.settings.adaptive;
  // Without --spp a target or a time budget alone decides when to stop
  // (`--time 60`: a minute's samples, not the scene's count or 60 s at
  // most). Adaptive rounds plan against a budget: with time alone it starts
  // at the scene's count and doubles each time it is spent.
  if (countOpen(cli)) {
    if (options.adaptive && !cli.targetRmse) {
      options.openEndedBudget = true;
    } else {
      options.samplesPerPixel = kMaxSamples;
    }
  }
  if (cli.targetRmse) options.targetRmse = *cli.targetRmse;
  options.estimateError = cli.estimateRmse || cli.targetRmse;
  options.keepErrorImage = !cli.errorMapPath.empty() || rt::isExrPath(cli.outputPath);
  options.seed = cli.seed;
  // A time budget stops part way through a pass: one sample a pass keeps
  // every pixel within one sample of the others.
  if (cli.timeBudget) options.maxPassSamples = 1;
  options.sampler = rt::cli::samplerNamed(
      cli.sampler, rt::samplerUnlessAsked(scene.settings, options.adaptive || countOpen(cli)));
  options.shading = rt::cli::shadingNamed(cli.shading);
  options.accel = rt::cli::accelNamed(cli.accel);
  options.sceneArrays = rt::cli::sceneArraysNamed(cli.sceneArrays);
  options.walks = rt::cli::walksNamed(cli.walks);
  if (!cli.sampleRange.empty()) parseSampleRange(cli.sampleRange, options);
  refuseSplitAdaptive(cli, options);
  checkMapOptions(cli, options);
  return options;
}

// --camera-path FILE --frame N: the scene's camera becomes the viewer's at
// that frame, and the image takes the frame's size.
void applyPathFrame(const CommandLine& cli, rt::Scene& scene, rt::RenderOptions& options) {
  if (cli.cameraPath.empty()) return;
  std::vector<rt::viewer::PathStep> steps = rt::viewer::loadCameraPath(cli.cameraPath);
  uint32_t width = options.width ? options.width : scene.camera.width;
  uint32_t height = options.height ? options.height : scene.camera.height;
  rt::cli::PathFrame frame =
      rt::cli::pathFrame(scene, steps, cli.cameraPath, cli.frame.value_or(0), width, height);
  options.frameOrigin = scene.camera.position;  // as the viewer encodes the scene
  scene.camera = frame.camera;
  options.width = frame.width;
  options.height = frame.height;
}

// --region X,Y,W,H: only those pixels get samples (tiles of one image that
// `raytracer merge` puts together, like sample ranges).
void applyRegion(const CommandLine& cli, const rt::Scene& scene, rt::RenderOptions& options) {
  if (cli.region.empty()) return;
  uint32_t width = options.width ? options.width : scene.camera.width;
  uint32_t height = options.height ? options.height : scene.camera.height;
  rt::PixelRegion region = rt::parseRegion(cli.region, "--region");
  try {
    options.region = rt::resolveRegion(region, width, height);
  } catch (const rt::Error& e) {
    throw rt::Error(fmt::format("--region: {}", e.what()));
  }
}

void printFrameCount(const CommandLine& cli) {
  std::printf("%u\n", rt::cli::pathFrameCount(rt::viewer::loadCameraPath(cli.cameraPath)));
}

std::string samplesText(const rt::RenderStats& stats) {
  if (stats.maxSamples == stats.samplesDone) return fmt::format("{} spp", stats.samplesDone);
  return fmt::format("{:.1f} spp on average ({}..{})", stats.meanSamples, stats.samplesDone,
                     stats.maxSamples);
}

std::string rmseText(const rt::RenderStats& stats) {
  if (!stats.rmseEstimate) return "";
  return fmt::format("; estimated RMSE {:.5f}{}", *stats.rmseEstimate,
                     stats.reachedTarget ? " (target reached)" : "");
}

uint64_t renderedPixels(const rt::RenderOptions& options, uint32_t width, uint32_t height) {
  if (options.region.wholeImage()) return uint64_t(width) * height;
  return uint64_t(options.region.width) * options.region.height;
}

// One line (its start, up to the seconds, is what rtfarm's worker parses).
void printSummary(const rt::ImageF& image, uint64_t pixels, const rt::Scene& scene,
                  const rt::RenderOptions& options, const rt::RenderStats& stats,
                  const rt::VulkanContext& context) {
  double samples = double(pixels) * stats.meanSamples;
  std::fprintf(stderr,
               "rendered %ux%u at %s in %.3f s (%.2f Msamples/s) on %s; "
               "%u primitives, features: %s; conventions: %s (%s); sampler %s; setup %.3f s, "
               "%u dispatches%s\n",
               image.width, image.height, samplesText(stats).c_str(), stats.renderSeconds,
               samples / std::max(stats.renderSeconds, 1e-9) * 1e-6,
               context.description().summary().c_str(), stats.primitives,
               stats.features.summary().c_str(), rt::conventionsName(scene.conventions),
               scene.conventionsReason.c_str(), rt::samplerKindName(options.sampler),
               stats.setupSeconds, stats.dispatches, rmseText(stats).c_str());
}

// The image (an EXR also gets the per-pixel sample count and, when
// estimated, error as layers), then the maps asked for.
void writeOutputs(const CommandLine& cli, const rt::ImageF& image, const rt::RenderStats& stats,
                  const rt::ToneMapping& mapping) {
  std::vector<rt::ExrLayer> layers{{"samples.Y", rt::sampleCountChannel(image)}};
  if (!stats.estimatedError.empty()) layers.push_back({"error.Y", stats.estimatedError});
  rt::writeImage(cli.outputPath, image, mapping, layers);
  if (!cli.sampleMapPath.empty()) rt::writeImage8(cli.sampleMapPath, rt::sampleCountMap(image));
  if (!cli.errorMapPath.empty()) {
    rt::writeImage8(cli.errorMapPath,
                    rt::errorMap(image.width, image.height, stats.estimatedError));
  }
}

int run(const CommandLine& cli) {
  if (!rt::isSupportedImageExtension(cli.outputPath)) {
    throw rt::Error(rt::unsupportedOutputMessage(cli.outputPath));
  }
  for (const std::string& path : {cli.outputPath, cli.sampleMapPath, cli.errorMapPath})
    if (!path.empty()) rt::checkWritable(path);
  rt::Scene scene = rt::loadSceneFile(cli.scenePath, {cli.strict});
  for (const std::string& warning : scene.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  rt::cli::applyConventionsOption(cli.conventions, scene);
  if (cli.indirectClamp) scene.settings.indirectClamp = *cli.indirectClamp;
  if (cli.roulette) scene.settings.rouletteWeight = *cli.roulette;
  if (cli.bailout) scene.settings.branchBailout = *cli.bailout;
  rt::cli::applyModeOptions(cli.modeOptions, scene);
  rt::cli::applyLightSamplesOption(cli.lightSamples, scene);
  rt::cli::applyLightSplitOption(cli.lightSplit, scene);
  rt::RenderOptions options = renderOptions(cli, scene);
  if (cli.sampler.empty() && scene.settings.samplerGiven &&
      scene.settings.sampler != options.sampler) {
    std::fprintf(stderr,
                 "warning: the scene's sampler (%s) is for uniform renders of a known count: %s "
                 "sample with %s (--sampler chooses)\n",
                 rt::samplerKindName(scene.settings.sampler),
                 options.adaptive ? "adaptive ones" : "renders that --time or --target-rmse ends",
                 rt::samplerKindName(options.sampler));
  }
  applyPathFrame(cli, scene, options);
  applyRegion(cli, scene, options);
  if (auto curve = rt::cli::toneCurveOption(cli.toneCurve)) scene.camera.toneCurve = *curve;
  options.displayMapping = rt::toneMappingFor(scene);
  if (cli.exposure) options.displayMapping->exposure *= *cli.exposure;

  rt::VulkanContext context(contextOptions(cli));
  rt::ShaderCompiler compiler(cli.shaderDir.empty() ? rt::ShaderCompiler::defaultShaderDir()
                                                    : std::filesystem::path(cli.shaderDir),
                              rt::ShaderCompiler::defaultCacheDir());
  rt::Renderer renderer(context, compiler);
  uint32_t width = options.width ? options.width : scene.camera.width;
  uint32_t height = options.height ? options.height : scene.camera.height;
  rt::ProgressBar progress(renderedPixels(options, width, height), !cli.quiet, cli.timeBudget,
                           !countOpen(cli));
  rt::RenderStats stats;
  installInterruptHandlers();
  auto start = rt::SteadyClock::now();
  options.shouldStop = [&] {
    return interrupted.load() || (cli.timeBudget && rt::secondsSince(start) >= *cli.timeBudget);
  };
  rt::ImageF image = renderer.render(
      scene, options, [&](const rt::RenderProgress& p) { progress.update(p); }, &stats);
  progress.finish();
  for (const std::string& warning : stats.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());

  writeOutputs(cli, image, stats, *options.displayMapping);
  if (stats.stoppedEarly) {
    const char* why = interrupted.load() ? "interrupted" : "time budget reached";
    if (options.adaptive) {
      std::fprintf(stderr, "%s at a mean of %.1f samples per pixel; wrote %s\n", why,
                   stats.meanSamples, cli.outputPath.c_str());
    } else {
      std::fprintf(stderr, "%s after %u full sample(s) per pixel; wrote %s\n", why,
                   stats.samplesDone, cli.outputPath.c_str());
    }
  }
  if (!cli.quiet) {
    printSummary(image, renderedPixels(options, width, height), scene, options, stats, context);
  }
  if (context.validationMessageCount() > 0) {
    throw rt::Error(
        fmt::format("{} Vulkan validation message(s) reported", context.validationMessageCount()));
  }
  return 0;
}

}  // namespace

int runRenderCommand(int argc, char** argv) {
  CommandLine cli;
  CLI::App app{"GPU compute ray tracer (Vulkan). Renders a scene to an image.", "raytracer"};
  app.set_version_flag("--version", std::string("raytracer ") + RT_VERSION);
  app.add_option("scene", cli.scenePath, rt::cli::kSceneFileHelp);
  app.add_option("output", cli.outputPath, std::string("Output image: ") + rt::kOutputFormats);
  app.add_option("--spp", cli.samples, "Samples per pixel (default: the scene's, else 16)")
      ->check(CLI::Range(1u, kMaxSamples));
  app.add_option("--size", cli.size, "Image size WIDTHxHEIGHT (overrides the scene)");
  app.add_option("--seed", cli.seed, "Random seed (renders are reproducible per seed)");
  app.add_option("--sampler", cli.sampler,
                 "Sampler of every random dimension: random, jittered or sobol (Owen-scrambled "
                 "Sobol); default: the scene's, else jittered; sobol for --adaptive, and where "
                 "--time or --target-rmse ends a render without --spp")
      ->check(rt::cli::samplerValidator());
  app.add_option("--shading", cli.shading,
                 "Shading model (default: the conventions': coursework for coursework-a, "
                 "standard otherwise)")
      ->check(CLI::IsMember({"standard", "coursework"}));
  rt::cli::addConventionsOption(app, cli.conventions);
  rt::cli::addStrictOption(app, cli.strict);
  rt::cli::addAccelOption(app, cli.accel);
  rt::cli::addSceneArraysOption(app, cli.sceneArrays);
  rt::cli::addWalksOption(app, cli.walks);
  app.add_flag("--offscreen", cli.offscreen, "Render without a window (the default)");
  app.add_option("--device", cli.device, "'list' to list Vulkan devices, or the number to use");
  app.add_flag("--validation", cli.validation,
               "Enable the Vulkan validation layer; any message fails the run");
  app.add_option("--shader-dir", cli.shaderDir,
                 "Folder with the GLSL shaders (default: built-in path)");
  app.add_option("--exposure", cli.exposure, "Extra exposure factor applied before tone mapping")
      ->check(rt::cli::positiveFiniteNumber());
  rt::cli::addToneCurveOption(app, cli.toneCurve);
  app.add_option("--clamp-indirect", cli.indirectClamp,
                 "Firefly clamp: the largest channel one light contribution may add after a "
                 "diffuse bounce (path tracer, distributedbounces; biased; 0 = off; overrides "
                 "the scene's clampindirect)")
      ->check(rt::cli::nonNegativeFiniteNumber());
  app.add_option("--roulette", cli.roulette,
                 "Russian roulette on mirror and refraction rays lighter than this weight "
                 "(unbiased; faster glass, a little more noise; e.g. 0.03; default 0 = off)")
      ->check(CLI::Range(0.0f, 1.0f));
  app.add_option("--bailout", cli.bailout,
                 "Mirror, glass and diffuse-bounce rays whose weight is below this, and shadow "
                 "rays that could add less to the pixel, are not traced (POV-Ray's adc_bailout; "
                 "in steps of the written image; default 1/255; 0 traces every ray down to "
                 "weight 1e-4; not in the path tracer)")
      ->check(CLI::Range(0.0f, 1.0f));
  rt::cli::addModeOptions(app, cli.modeOptions);
  rt::cli::addLightSamplesOption(app, cli.lightSamples);
  rt::cli::addLightSplitOption(app, cli.lightSplit);
  app.add_option("--samples", cli.sampleRange,
                 "Render only sample indices FROM:TO of the --spp samples (merge the pieces "
                 "with `raytracer merge`; write .exr, whose alpha holds the sample count)");
  app.add_option("--region", cli.region,
                 "Render only the pixels X,Y,WIDTH,HEIGHT (the others keep no samples; merge "
                 "tiles with `raytracer merge`, like sample ranges)");
  auto* cameraPath =
      app.add_option("--camera-path", cli.cameraPath,
                     "Render a frame of a viewer camera path (see src/viewer/CameraPath.hpp)");
  app.add_option("--frame", cli.frame, "The frame of --camera-path to render (default 0)")
      ->needs(cameraPath);
  app.add_flag("--frame-count", cli.frameCount,
               "Print how many frames --camera-path lasts and exit")
      ->needs(cameraPath);
  app.add_option("--time", cli.timeBudget,
                 "Stop after this many seconds, the setup included (every sample done is kept; "
                 "passes of one sample, so that every pixel has as many as the others, or one "
                 "more; never fewer than one sample a pixel). Without --spp the "
                 "time alone decides: as many samples as fit (adaptive: the scene's budget, "
                 "doubled each time it is spent)")
      ->check(rt::cli::positiveFiniteNumber());
  app.add_option("--target-rmse", cli.targetRmse,
                 "Stop once the estimated RMSE of the displayed image (0..1 values, see README "
                 "'Speed vs accuracy') is at most this; --spp (default: no limit) and --time "
                 "still stop it first")
      ->check(rt::cli::positiveFiniteNumber());
  app.add_flag("--estimate-rmse", cli.estimateRmse,
               "Estimate the displayed image's RMSE while rendering (even and odd samples become "
               "independent halves, which costs jittered and sobol some accuracy)");
  app.add_flag("--adaptive", cli.adaptive,
               "Adaptive sampling: after a first pass of 1.25 samples per pixel, rounds give "
               "more samples to the noisiest 8x8 tiles, weighed by the rays their samples trace; "
               "--spp is then the budget of the mean count per pixel, --target-rmse the goal "
               "(sampler: sobol unless --sampler names another, whatever the scene names; "
               "cannot be split with --samples or --region)");
  app.add_option("--sample-map", cli.sampleMapPath,
                 "Also write a .png of the samples each pixel got (false colour, log scale)");
  app.add_option("--error-map", cli.errorMapPath,
                 "Also write a .png of each pixel's estimated error (needs --adaptive, "
                 "--estimate-rmse or --target-rmse)");
  app.add_flag("-q,--quiet", cli.quiet, "No progress bar or summary");
  app.footer(
      "Other commands (each with its own --help):\n"
      "  raytracer view SCENE            interactive window: progressive, hot-reloaded shaders\n"
      "  raytracer converge SCENE        error against samples and time, per sampler\n"
      "  raytracer merge PART.exr... OUT combine split renders (--samples, --region)\n"
      "  raytracer check SCENE           how the scene file is read, without rendering");
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    if (cli.device == "list") {
      listDevices();
      return 0;
    }
    if (cli.frameCount) {
      printFrameCount(cli);
      return 0;
    }
    if (cli.scenePath.empty() || cli.outputPath.empty()) {
      std::fprintf(stderr,
                   "error: usage: raytracer SCENE.json OUTPUT.png [options], or raytracer "
                   "view|converge|merge|check ... (see --help)\n");
      return 2;
    }
    return run(cli);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
