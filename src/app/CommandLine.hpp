// Command-line pieces every subcommand shares: parsing with one-line errors,
// and the values several commands accept (--size, --device, --sampler,
// --shading).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "encode/Conventions.hpp"
#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "encode/SceneBuffers.hpp"
#include "scene/Limits.hpp"
#include "scene/Scene.hpp"

namespace rt::cli {

constexpr uint32_t kMaxSamples = kMaxSamplesPerPixel;

// The help of every command's scene argument: the files formats/SceneFile reads.
constexpr const char* kSceneFileHelp = "Scene file (.json, or a .gltf/.glb, .obj or .ply model)";

// Parses argv into `app`. Returns an exit status when the command should end
// now (--help, --version: 0; a usage error, reported in one line: 2).
std::optional<int> parse(CLI::App& app, int argc, char** argv);

struct Size {
  uint32_t width = 0;
  uint32_t height = 0;
};

// Checks that an option is a positive, finite number (CLI::PositiveNumber
// lets NaN through and prints DBL_MAX in full).
CLI::Validator positiveFiniteNumber();
// The same with 0 allowed.
CLI::Validator nonNegativeFiniteNumber();

// "WIDTHxHEIGHT", each side 1..kMaxImageSide; throws rt::Error naming --size.
Size parseSize(const std::string& text);

// A device number for --device; throws rt::Error naming the text.
uint32_t parseDeviceIndex(const std::string& text);

// A sampler name (see samplerKindNamed) or "" (keep `fallback`); throws
// rt::Error naming --sampler for anything else.
SamplerKind samplerNamed(const std::string& name, SamplerKind fallback);
// Accepts the names samplerNamed knows (a usage error otherwise).
CLI::Validator samplerValidator();

// "standard" / "coursework" / "" (the conventions' default).
std::optional<ShadingModel> shadingNamed(const std::string& name);

// --accel bvh|none|hardware into `name`; accelNamed turns it into the kind
// ("" is bvh, the default).
void addAccelOption(CLI::App& app, std::string& name);
AccelKind accelNamed(const std::string& name);

// --scene-arrays texel|storage into `name`; sceneArraysNamed turns it into
// the kind (empty: texel).
void addSceneArraysOption(CLI::App& app, std::string& name);
SceneArrays sceneArraysNamed(const std::string& name);

// --walks paired|single into `name`; walksNamed turns it into the kind
// (empty: paired).
void addWalksOption(CLI::App& app, std::string& name);
Walks walksNamed(const std::string& name);

// --conventions NAME (coursework-a, coursework-b, textbook) into `name`.
void addConventionsOption(CLI::App& app, std::string& name);
// --tone-curve clamp|reinhard|aces: the scene's tone curve replaced.
void addToneCurveOption(CLI::App& app, std::string& name);
std::optional<ToneCurve> toneCurveOption(const std::string& name);  // nullopt when not given
// --strict into `strict`: every warning about the scene file is an error.
void addStrictOption(CLI::App& app, bool& strict);

// Gives a loaded scene the conventions --conventions named, if any.
void applyConventionsOption(const std::string& name, Scene& scene);

// --mode binary|phong|pathtracer and --bounces N: the scene's `rendermode`
// and `nbounces`, for model files (which have neither) and quick changes.
struct ModeOptions {
  std::string mode;  // "" or a name renderModeNamed knows
  std::optional<uint32_t> bounces;
};
std::optional<RenderMode> renderModeNamed(const std::string& name);
void addModeOptions(CLI::App& app, ModeOptions& options);
// Gives a loaded scene the mode and bounces the options named, if any.
void applyModeOptions(const ModeOptions& options, Scene& scene);

// --light-samples N into `samples`: shadow rays per area light and hit.
void addLightSamplesOption(CLI::App& app, std::optional<uint32_t>& samples);
// Gives every area light of a loaded scene the count --light-samples named,
// if any (a warning when the scene has none).
void applyLightSamplesOption(const std::optional<uint32_t>& samples, Scene& scene);

// --light-split K into `replicas`: each hit's area-light estimate K times over.
void addLightSplitOption(CLI::App& app, std::optional<uint32_t>& replicas);
// Gives a loaded scene the light splitting --light-split named, if any (a
// warning when the scene has no area lights).
void applyLightSplitOption(const std::optional<uint32_t>& replicas, Scene& scene);

}  // namespace rt::cli
