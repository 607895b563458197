// What both the offline renderer and the progressive one are told about the
// image and its samples: size, pixels, sampler, shading and traversal.
#pragma once

#include <cstdint>
#include <optional>

#include "encode/Conventions.hpp"
#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "encode/SceneBuffers.hpp"
#include "imaging/PixelRegion.hpp"
#include "scene/Scene.hpp"

namespace rt {

struct ImageSampling {
  uint32_t width = 0;  // 0: the scene camera's size
  uint32_t height = 0;
  PixelRegion region;  // pixels rendered (empty: all); the others keep no samples
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Jittered;
  std::optional<ShadingModel> shading;  // default: the scene family's
  bool countRays = false;               // compile in a ray counter (benchmarks)
  AccelKind accel = AccelKind::Bvh;     // none: brute force, to compare against
  // How kernels read the scene arrays; the image does not depend on it.
  SceneArrays sceneArrays = SceneArrays::TexelBuffers;
  // Rays that start together walk the BVH in pairs or one by one; the image
  // does not depend on it.
  Walks walks = Walks::Paired;
  // Pixels from a queue on CPU devices, or a workgroup per block; the image
  // does not depend on it.
  WorkQueue workQueue = WorkQueue::OnCpu;
  // Origin of the GPU's coordinates (FlattenOptions::frameOrigin).
  std::optional<WorldPoint> frameOrigin;
  // How the image is shown (default: toneMappingFor(scene)), `--exposure`
  // included: the error estimate measures in it and the ray tree's bailout
  // counts its steps (FlattenOptions::displayMapping).
  std::optional<ToneMapping> displayMapping;
};

}  // namespace rt
