// raytracer converge SCENE [options]: error against a reference as the
// sample count grows, per sampler; writes PREFIX.csv and PREFIX.png and
// prints fitted slopes and the cost of reaching a target error. A thin
// client of render/Convergence.hpp.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "encode/Conventions.hpp"
#include "formats/SceneFile.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "imaging/Convergence.hpp"
#include "io/AtomicFile.hpp"
#include "io/Image.hpp"
#include "io/Plot.hpp"
#include "render/Renderer.hpp"
#include "util/Error.hpp"

namespace {

constexpr uint32_t kFirstSamples = 9;
constexpr uint32_t kDefaultMaxSamples = 1024;
constexpr double kSeriesRatio = 1.4142135623730951;  // two counts per octave
constexpr uint32_t kReferenceFactor = 8;             // default reference: 8x the largest count

struct CommandLine {
  std::string scenePath;
  bool strict = false;
  std::string referencePath;
  std::optional<uint32_t> referenceSamples;
  std::string region;
  std::vector<std::string> samplers{"random", "jittered", "sobol"};
  std::vector<uint32_t> sampleList;
  std::optional<uint32_t> maxSamples;
  std::string outPrefix;
  std::string size;
  uint32_t seed = 0;
  double targetRmse = 0.01;
  std::string clock = "wall";
  bool estimate = false;
  uint32_t repeats = 1;
  std::string shading;
  std::optional<float> roulette;
  std::optional<float> bailout;
  std::optional<uint32_t> lightSamples;
  rt::cli::ModeOptions modeOptions;
  std::optional<uint32_t> lightSplit;
  std::string conventions;
  std::string device;
  std::string shaderDir;
  bool validation = false;
  bool quiet = false;
};

std::vector<uint32_t> sampleCounts(const CommandLine& cli) {
  if (!cli.sampleList.empty()) {
    std::vector<uint32_t> counts = cli.sampleList;
    std::sort(counts.begin(), counts.end());
    counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
    if (counts.size() < 2) throw rt::Error("--spp-list: give at least two different counts");
    return counts;
  }
  uint32_t last = cli.maxSamples.value_or(kDefaultMaxSamples);
  if (last <= kFirstSamples) {
    throw rt::Error(fmt::format("--max-spp {}: must be above {}", last, kFirstSamples));
  }
  return rt::geometricSampleCounts(kFirstSamples, last, kSeriesRatio);
}

rt::ConvergenceSetup convergenceSetup(const CommandLine& cli, const rt::Scene& scene) {
  rt::ConvergenceSetup setup;
  if (!cli.size.empty()) {
    rt::cli::Size size = rt::cli::parseSize(cli.size);
    setup.width = size.width;
    setup.height = size.height;
  }
  uint32_t width = setup.width ? setup.width : scene.camera.width;
  uint32_t height = setup.height ? setup.height : scene.camera.height;
  if (!cli.region.empty()) {
    setup.region = rt::resolveRegion(rt::parseRegion(cli.region, "--region"), width, height);
  }
  setup.seed = cli.seed;
  setup.shading = rt::cli::shadingNamed(cli.shading);
  setup.mapping = rt::toneMappingFor(scene);
  setup.estimateError = cli.estimate;
  setup.repeats = cli.repeats;
  return setup;
}

// The reference from a file written by `raytracer SCENE REF.exr`, which
// applies the exposure: it is undone here so both sides map alike.
rt::ImageF loadReference(const CommandLine& cli, const rt::ConvergenceSetup& setup,
                         const rt::Scene& scene) {
  rt::ImageF reference = rt::readExr(cli.referencePath);
  uint32_t width = setup.width ? setup.width : scene.camera.width;
  uint32_t height = setup.height ? setup.height : scene.camera.height;
  if (reference.width != width || reference.height != height) {
    throw rt::Error(fmt::format("{}: the reference is {}x{} but the renders are {}x{} (--size)",
                                cli.referencePath, reference.width, reference.height, width,
                                height));
  }
  for (size_t i = 0; i < reference.rgba.size(); ++i) {
    if (i % 4 != 3) reference.rgba[i] /= setup.mapping.exposure;
  }
  return reference;
}

void printSummaryTable(const std::vector<rt::ConvergencePoint>& points,
                       const std::vector<rt::SeriesKind>& samplers, double target,
                       rt::ConvergenceClock clock) {
  std::printf(
      "%-9s %8s %14s %14s\n", "sampler", "slope", fmt::format("spp@{:g}", target).c_str(),
      fmt::format("{}@{:g}", clock == rt::ConvergenceClock::Cpu ? "cpu_s" : "seconds", target)
          .c_str());
  for (const rt::SeriesKind& kind : samplers) {
    std::vector<rt::ConvergencePoint> own;
    for (const auto& p : points) {
      if (p.series() == kind) own.push_back(p);
    }
    rt::ConvergenceSummary s = rt::summarizeConvergence(own, target, clock);
    const char* mark = s.extrapolated ? "~" : "";
    std::printf("%-9s %8.3f %13s%s %13s%s\n", rt::seriesName(kind), s.slope,
                fmt::format("{:.0f}", s.samplesToTarget).c_str(), mark,
                fmt::format("{:.3f}", s.secondsToTarget).c_str(), mark);
  }
  std::printf("(~: extrapolated from the fitted power law; otherwise interpolated)\n");
}

int run(const CommandLine& cli) {
  rt::Scene scene = rt::loadSceneFile(cli.scenePath, {cli.strict});
  if (cli.roulette) scene.settings.rouletteWeight = *cli.roulette;
  if (cli.bailout) scene.settings.branchBailout = *cli.bailout;
  rt::cli::applyModeOptions(cli.modeOptions, scene);
  rt::cli::applyLightSamplesOption(cli.lightSamples, scene);
  rt::cli::applyLightSplitOption(cli.lightSplit, scene);
  rt::cli::applyConventionsOption(cli.conventions, scene);
  rt::ConvergenceSetup setup = convergenceSetup(cli, scene);
  std::vector<uint32_t> counts = sampleCounts(cli);
  std::vector<rt::SeriesKind> samplers;
  for (const std::string& name : cli.samplers) {
    std::optional<rt::SeriesKind> kind = rt::seriesNamed(name);
    if (!kind) throw rt::Error(fmt::format("--samplers: unknown sampler '{}'", name));
    samplers.push_back(*kind);
  }
  std::string prefix = cli.outPrefix.empty()
                           ? std::filesystem::path(cli.scenePath).stem().string() + "-converge"
                           : cli.outPrefix;
  for (const char* suffix : {".csv", ".png", "-reference.exr"}) rt::checkWritable(prefix + suffix);

  rt::ContextOptions contextOptions;
  contextOptions.validation = cli.validation;
  if (!cli.device.empty()) contextOptions.deviceIndex = rt::cli::parseDeviceIndex(cli.device);
  rt::VulkanContext context(contextOptions);
  rt::ShaderCompiler compiler(cli.shaderDir.empty() ? rt::ShaderCompiler::defaultShaderDir()
                                                    : std::filesystem::path(cli.shaderDir),
                              rt::ShaderCompiler::defaultCacheDir());
  rt::Renderer renderer(context, compiler);
  rt::ConvergenceStudy study(renderer, scene, setup);

  rt::ImageF reference;
  if (!cli.referencePath.empty()) {
    reference = loadReference(cli, setup, scene);
  } else {
    uint32_t samples = cli.referenceSamples.value_or(kReferenceFactor * counts.back());
    if (!cli.quiet) std::fprintf(stderr, "rendering the reference (sobol, %u spp)\n", samples);
    reference = study.renderReference(samples);
    rt::writeImage(prefix + "-reference.exr", reference, setup.mapping);
  }

  const rt::ConvergenceClock clock =
      cli.clock == "cpu" ? rt::ConvergenceClock::Cpu : rt::ConvergenceClock::Wall;
  std::vector<rt::ConvergencePoint> points;
  for (const rt::SeriesKind& kind : samplers) {
    auto onPoint = [&](const rt::ConvergencePoint& p) {
      if (cli.quiet) return;
      std::fprintf(stderr, "%-8s %6u spp  RMSE %.5f (estimated %s)  %.3f s (CPU %.3f s)\n",
                   rt::seriesName(kind), p.samples, p.rmse,
                   p.estimatedRmse ? fmt::format("{:.5f}", *p.estimatedRmse).c_str() : "-",
                   p.seconds, p.cpuSeconds);
    };
    std::vector<rt::ConvergencePoint> own = study.measure(reference, kind, counts, onPoint);
    points.insert(points.end(), own.begin(), own.end());
  }

  std::string csv = rt::convergenceCsv(points);
  rt::writeFileAtomically(prefix + ".csv", csv.data(), csv.size());
  std::string title = std::filesystem::path(cli.scenePath).stem().string();
  rt::writeImage8(prefix + ".png", rt::drawLogLogPlot(rt::convergencePlotPanels(
                                       points, cli.targetRmse, title, clock)));
  printSummaryTable(points, samplers, cli.targetRmse, clock);
  if (!cli.quiet) std::fprintf(stderr, "wrote %s.csv and %s.png\n", prefix.c_str(), prefix.c_str());
  if (context.validationMessageCount() > 0) {
    throw rt::Error(
        fmt::format("{} Vulkan validation message(s) reported", context.validationMessageCount()));
  }
  return 0;
}

void addOptions(CLI::App& app, CommandLine& cli) {
  app.add_option("scene", cli.scenePath, rt::cli::kSceneFileHelp)->required();
  auto* reference =
      app.add_option("--reference", cli.referencePath,
                     "Reference image (.exr as written by `raytracer SCENE REF.exr`)");
  app.add_option("--reference-spp", cli.referenceSamples,
                 "Samples per pixel of the rendered reference (sobol; default 8x the largest "
                 "count); it is also written to PREFIX-reference.exr")
      ->check(CLI::Range(1u, rt::cli::kMaxSamples))
      ->excludes(reference);
  app.add_option("--region", cli.region, "Render and measure only X,Y,WIDTH,HEIGHT");
  app.add_option("--samplers", cli.samplers,
                 "Samplers to compare: random, jittered, sobol and adaptive (adaptive sampling "
                 "on sobol, --spp as the mean count; default random,jittered,sobol)")
      ->delimiter(',')
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            return rt::seriesNamed(name) ? "" : "expected random, jittered, sobol or adaptive";
          },
          "SAMPLER"));
  auto* list = app.add_option("--spp-list", cli.sampleList, "Sample counts, e.g. 9,16,64,256")
                   ->delimiter(',')
                   ->check(CLI::Range(1u, rt::cli::kMaxSamples));
  app.add_option("--max-spp", cli.maxSamples,
                 "Largest count of the default series 9, 13, 18, ... (x sqrt 2; default 1024)")
      ->check(CLI::Range(1u, rt::cli::kMaxSamples))
      ->excludes(list);
  app.add_option("--out", cli.outPrefix, "Output prefix (default: SCENE-converge)");
  app.add_option("--size", cli.size, "Image size WIDTHxHEIGHT (overrides the scene)");
  app.add_option("--seed", cli.seed, "Seed of the measured renders");
  app.add_option("--target", cli.targetRmse, "RMSE whose cost the table reports (default 0.01)")
      ->check(CLI::PositiveNumber);
  app.add_option("--clock", cli.clock,
                 "Time of the table and plot: wall (default) or cpu (process CPU time, all "
                 "threads: lavapipe's work, robust on a busy machine); the CSV has both")
      ->check(CLI::IsMember({"wall", "cpu"}));
  app.add_option("--repeat", cli.repeats,
                 "Renders of each point; the times are their medians (default 1)")
      ->check(CLI::Range(1, 99));
  app.add_flag("--estimate", cli.estimate,
               "Render as for --estimate-rmse (independent even/odd halves) and record the "
               "renderer's own RMSE estimate beside the true one");
  app.add_option("--roulette", cli.roulette, "Russian roulette weight (as the render command)")
      ->check(CLI::Range(0.0f, 1.0f));
  app.add_option("--bailout", cli.bailout, "Ray-tree bailout weight (as the render command)")
      ->check(CLI::Range(0.0f, 1.0f));
  rt::cli::addModeOptions(app, cli.modeOptions);
  rt::cli::addLightSamplesOption(app, cli.lightSamples);
  rt::cli::addLightSplitOption(app, cli.lightSplit);
  app.add_option("--shading", cli.shading, "Shading model (default: the conventions')")
      ->check(CLI::IsMember({"standard", "coursework"}));
  rt::cli::addConventionsOption(app, cli.conventions);
  rt::cli::addStrictOption(app, cli.strict);
  app.add_option("--device", cli.device, "The number of the Vulkan device to use");
  app.add_flag("--validation", cli.validation, "Enable the Vulkan validation layer");
  app.add_option("--shader-dir", cli.shaderDir, "Folder with the GLSL shaders");
  app.add_flag("-q,--quiet", cli.quiet, "Only the summary table");
}

}  // namespace

int runConvergeCommand(int argc, char** argv) {
  CommandLine cli;
  CLI::App app{
      "Measures RMSE against a reference as samples grow, per sampler (CSV, log-log plot, "
      "fitted slopes)",
      "raytracer converge"};
  addOptions(app, cli);
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    return run(cli);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
