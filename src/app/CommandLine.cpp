#include "app/CommandLine.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "formats/json/JsonSceneLoader.hpp"
#include "util/Error.hpp"

namespace rt::cli {

std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s (see %s --help)\n", e.what(), app.get_name().c_str());
    return 2;
  }
  return std::nullopt;
}

namespace {

// A finite number of at least `low` (or above it when `low` is excluded).
CLI::Validator finiteNumberAbove(double low, bool lowAllowed, const std::string& what,
                                 const std::string& name) {
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool inRange = lowAllowed ? value >= low : value > low;
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || !inRange) {
          return "must be a " + what + ", finite number, got '" + text + "'";
        }
        return {};
      },
      name);
}

// The light options change nothing in a scene without area lights.
void warnWithoutAreaLights(const char* option, const Scene& scene) {
  if (scene.areaLights.empty()) {
    std::fprintf(stderr, "warning: %s: the scene has no area lights\n", option);
  }
}

}  // namespace

CLI::Validator positiveFiniteNumber() {
  return finiteNumberAbove(0.0, false, "positive", "POSITIVE");
}

CLI::Validator nonNegativeFiniteNumber() {
  return finiteNumberAbove(0.0, true, "non-negative", "NON-NEGATIVE");
}

Size parseSize(const std::string& text) {
  static const std::regex pattern(R"((\d{1,9})x(\d{1,9}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw Error(fmt::format("--size {}: expected WIDTHxHEIGHT, e.g. 800x600", text));
  }
  Size size{static_cast<uint32_t>(std::stoul(match[1].str())),
            static_cast<uint32_t>(std::stoul(match[2].str()))};
  if (size.width == 0 || size.height == 0 || size.width > kMaxImageSide ||
      size.height > kMaxImageSide) {
    throw Error(fmt::format("--size {}: each side must be 1..{}", text, kMaxImageSide));
  }
  return size;
}

uint32_t parseDeviceIndex(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
      text.size() > 6) {
    throw Error(fmt::format("--device {}: expected 'list' or a device number", text));
  }
  return static_cast<uint32_t>(std::stoul(text));
}

SamplerKind samplerNamed(const std::string& name, SamplerKind fallback) {
  if (name.empty()) return fallback;
  if (std::optional<SamplerKind> kind = samplerKindNamed(name)) return *kind;
  throw Error(fmt::format("--sampler {}: expected random, jittered or sobol", name));
}

CLI::Validator samplerValidator() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        return samplerKindNamed(name) ? "" : "expected random, jittered or sobol";
      },
      "SAMPLER");
}

std::optional<ShadingModel> shadingNamed(const std::string& name) {
  if (name == "standard") return ShadingModel::Standard;
  if (name == "coursework") return ShadingModel::Coursework;
  return std::nullopt;
}

void addAccelOption(CLI::App& app, std::string& name) {
  app.add_option("--accel", name,
                 "Acceleration: bvh (the default: the renderer's own BVH), none (every ray "
                 "tests every primitive) or hardware (the driver's acceleration structures "
                 "through ray queries: GPUs with ray tracing units; Mesa 25's lavapipe has them "
                 "in software)")
      ->check(CLI::IsMember({"bvh", "none", "hardware"}));
}

AccelKind accelNamed(const std::string& name) {
  if (name == "none") return AccelKind::None;
  if (name == "hardware") return AccelKind::Hardware;
  return AccelKind::Bvh;
}

void addSceneArraysOption(CLI::App& app, std::string& name) {
  app.add_option("--scene-arrays", name,
                 "How kernels read the scene: texel (texel buffers, the default: the faster on "
                 "lavapipe and on an NVIDIA H200) or storage (storage buffers of the same bytes, "
                 "to measure other GPUs); the image is the same. Mesa 25's lavapipe at vector "
                 "widths other than 256 bits (LP_NATIVE_VECTOR_WIDTH) misreads texel buffers: "
                 "there storage buffers are always used, with a warning")
      ->check(CLI::IsMember({"texel", "storage"}));
}

SceneArrays sceneArraysNamed(const std::string& name) {
  return name == "storage" ? SceneArrays::StorageBuffers : SceneArrays::TexelBuffers;
}

void addWalksOption(CLI::App& app, std::string& name) {
  app.add_option("--walks", name,
                 "How rays that start together walk the BVH: paired (the default, the faster on "
                 "lavapipe: a hit's shadow rays two by two, binary mode's primary rays two "
                 "samples at a time) or single (one walk a ray, to measure other GPUs); the "
                 "image is the same")
      ->check(CLI::IsMember({"paired", "single"}));
}

Walks walksNamed(const std::string& name) {
  return name == "single" ? Walks::Single : Walks::Paired;
}

void addConventionsOption(CLI::App& app, std::string& name) {
  app.add_option(
         "--conventions", name,
         "Conventions (light falloff, shading, ambient, mirrors, image orientation): "
         "coursework-a, coursework-b, textbook or physical; default: what the scene's keys say "
         "(README 'Conventions')")
      ->check(CLI::IsMember({"coursework-a", "coursework-b", "textbook", "physical"}));
}

void addToneCurveOption(CLI::App& app, std::string& name) {
  app.add_option("--tone-curve", name,
                 "Tone curve after the exposure: clamp (the courseworks'), reinhard (x / (1 + x)) "
                 "or aces (Narkowicz's filmic fit); default: the scene's (tone_mapping, "
                 "use_tone_mapping), else clamp")
      ->check(CLI::IsMember({"clamp", "reinhard", "aces"}));
}

std::optional<ToneCurve> toneCurveOption(const std::string& name) {
  if (name.empty()) return std::nullopt;
  return toneCurveNamed(name);
}

void addStrictOption(CLI::App& app, bool& strict) {
  app.add_flag("--strict", strict,
               "Every warning about the scene file (a missing texture or mesh file, a default "
               "taken for a missing key, an unknown key) is an error: exit 1, nothing rendered");
}

void applyConventionsOption(const std::string& name, Scene& scene) {
  if (name.empty()) return;
  std::optional<Conventions> conventions = conventionsNamed(name);
  if (!conventions) throw Error(fmt::format("--conventions {}: unknown conventions", name));
  setConventions(scene, *conventions, "--conventions");
}

std::optional<RenderMode> renderModeNamed(const std::string& name) {
  if (name == "binary") return RenderMode::Binary;
  if (name == "phong") return RenderMode::Phong;
  if (name == "pathtracer") return RenderMode::PathTracer;
  return std::nullopt;
}

void addModeOptions(CLI::App& app, ModeOptions& options) {
  app.add_option("--mode", options.mode,
                 "Render mode (overrides the scene's rendermode): binary (hits in one colour), "
                 "phong (Whitted: Blinn-Phong, shadows, mirror and glass) or pathtracer")
      ->check(CLI::IsMember({"binary", "phong", "pathtracer"}));
  app.add_option("--bounces", options.bounces,
                 "Ray depth (overrides the scene's nbounces): Whitted's mirror and glass "
                 "depth, or the path tracer's path length")
      ->check(CLI::Range(0u, kMaxBounces));
}

void applyModeOptions(const ModeOptions& options, Scene& scene) {
  if (std::optional<RenderMode> mode = renderModeNamed(options.mode)) scene.settings.mode = *mode;
  if (options.bounces) scene.settings.maxBounces = *options.bounces;
}

void addLightSamplesOption(CLI::App& app, std::optional<uint32_t>& samples) {
  app.add_option("--light-samples", samples,
                 "Shadow rays per area light and hit, for every area light (overrides the "
                 "scene's samples: fewer noisy shadows a sample, more time a sample; in the "
                 "coursework shading model, which clamps a hit's summed light, the image too)")
      ->check(CLI::Range(1u, kMaxLightSamples));
}

void applyLightSamplesOption(const std::optional<uint32_t>& samples, Scene& scene) {
  if (!samples) return;
  warnWithoutAreaLights("--light-samples", scene);
  setAreaLightSamples(scene, *samples);
}

void addLightSplitOption(CLI::App& app, std::optional<uint32_t>& replicas) {
  app.add_option("--light-split", replicas,
                 "Light splitting: each hit's area-light estimate is made K times over, each "
                 "with its own shadow rays and through the hit's whole shading, and averaged: "
                 "less shadow noise a sample for more time a sample, and the same image (where "
                 "--light-samples changes it in the coursework shading model); default 1, "
                 "and in adaptive renders enough for four area-light shadow rays a hit")
      ->check(CLI::Range(1u, kMaxLightSplit));
}

void applyLightSplitOption(const std::optional<uint32_t>& replicas, Scene& scene) {
  if (!replicas) return;
  warnWithoutAreaLights("--light-split", scene);
  scene.settings.lightSplit = *replicas;
}

}  // namespace rt::cli
