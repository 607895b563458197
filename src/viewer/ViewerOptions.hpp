// Everything `raytracer view` can be told on its command line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "encode/Conventions.hpp"
#include "scene/Scene.hpp"

namespace rt::viewer {

struct ViewerOptions {
  std::filesystem::path scenePath;
  uint32_t width = 0;  // initial window (and render) size; 0: the scene camera's
  uint32_t height = 0;
  std::optional<uint32_t> samplesTarget;  // default: the scene's spp, else 16 (as the CLI)
  uint32_t samplesPerFrame = 0;           // 0: adaptive bands of about frameSeconds
  double frameSeconds = 0.075;
  uint32_t frames = 0;  // exit after this many frames; 0: when the window closes
  std::filesystem::path cameraPath;
  std::filesystem::path screenshot;  // written from the last presented frame
  std::filesystem::path saveFolder = ".";
  bool overlay = true;
  std::filesystem::path shaderDir;  // empty: ShaderCompiler::defaultShaderDir()
  bool watch = true;                // hot reload of shaders and scene
  bool validation = false;
  std::optional<uint32_t> deviceIndex;
  uint32_t seed = 0;
  std::optional<SamplerKind> sampler;
  bool adaptive = false;  // adaptive sampling (also when the scene asks for it)
  std::optional<ShadingModel> shading;
  std::optional<Conventions> conventions;  // default: what the scene's keys say
  std::optional<ToneCurve> toneCurve;      // default: the scene's
  std::optional<RenderMode> mode;          // default: the scene's rendermode
  std::optional<uint32_t> bounces;         // default: the scene's nbounces (a slider after)
  float exposure = 1.0f;                   // extra factor on the scene's exposure
  std::optional<uint32_t> lightSamples;    // every area light's shadow rays a hit
  std::optional<uint32_t> lightSplit;      // replicas of a hit's area-light estimate
  bool verbose = false;                    // a log line every frame (otherwise about once a second)
};

// Runs the viewer until the window closes, --frames are done, or SIGINT /
// SIGTERM; returns the exit status. Throws rt::Error on setup failures.
int runViewer(const ViewerOptions& options);

}  // namespace rt::viewer
