#include "encode/Features.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <variant>

#include "util/Arithmetic.hpp"
#include "util/Text.hpp"

namespace rt {
namespace {

// Beyond this many pending rays the tracer follows one branch at random
// (unbiased), which bounds per-invocation memory for deep glass scenes.
constexpr uint32_t kMaxWhittedStack = 24;

void addGeometryFeatures(const Shape& shape, ShaderFeatures& features) {
  std::visit(
      [&](const auto& geometry) {
        using T = std::decay_t<decltype(geometry)>;
        if constexpr (std::is_same_v<T, Sphere>) features.spheres = true;
        if constexpr (std::is_same_v<T, Cylinder>) features.cylinders = true;
        if constexpr (std::is_same_v<T, Triangle> || std::is_same_v<T, Quad> ||
                      std::is_same_v<T, MeshInstance>) {
          features.triangles = true;
        }
        if constexpr (std::is_same_v<T, MeshInstance>) features.meshes = true;
      },
      shape.geometry);
}

// A mesh used once is built in world space: its instance's world-to-object
// rows are the identity.
bool movesRayIntoObjectSpace(const gpu::GpuPrimitive& primitive) {
  return primitive.kind == RT_PRIM_INSTANCE &&
         (primitive.a != glm::vec4(1, 0, 0, 0) || primitive.b != glm::vec4(0, 1, 0, 0) ||
          primitive.c != glm::vec4(0, 0, 1, 0));
}

// Light splitting where the scene does not set it (RenderSettings::lightSplit
// 0): adaptive renders of direct light (no path tracer, no sampled diffuse
// bounces) trace at least four area-light shadow rays a hit. Their rounds go
// to the noisiest tiles, penumbrae among them, where the light's sampling is
// the noise: on the area-light study four replicas took adaptive sampling to
// RMSE 0.01 in 0.062 CPU-seconds against 0.094 with one, 0.085 with two,
// 0.078 with eight (uniform jittered: 0.087, and no faster with four); the
// common scene's thin lens within noise of one. Where paths bounce, the
// indirect light is the noise: the path-traced Cornell box's adaptive renders
// had the same error with four replicas at 1.7x the time (README "Speed vs
// accuracy").
uint32_t lightReplicasFor(const RenderSettings& settings, bool adaptive, bool bounces,
                          uint32_t areaLightSamples) {
  constexpr uint32_t kAdaptiveAreaShadowRays = 4;
  if (settings.lightSplit > 0) return settings.lightSplit;
  if (!adaptive || bounces || areaLightSamples == 0) return 1;
  return divideRoundUp(kAdaptiveAreaShadowRays, areaLightSamples);
}

// Some shape places a mesh with vertex colours.
bool usesVertexColors(const Scene& scene) {
  return std::any_of(scene.shapes.begin(), scene.shapes.end(), [&](const Shape& shape) {
    return hasVertexColors(shape.geometry, scene.meshes);
  });
}

}  // namespace

ShaderFeatures detectFeatures(const Scene& scene, const FlatScene& flat, bool adaptive) {
  ShaderFeatures features;
  for (const Shape& shape : scene.shapes) addGeometryFeatures(shape, features);
  for (const gpu::GpuPrimitive& primitive : flat.primitives) {
    features.looseTriangles |= primitive.kind == RT_PRIM_TRIANGLE;
    features.instanceTransforms |= movesRayIntoObjectSpace(primitive);
    features.alphaCutouts |= (primitive.flags & RT_PRIM_ALPHA_CUTOUT) != 0u;
  }
  features.binaryOnly = scene.settings.mode == RenderMode::Binary;
  features.hardwareAccel = flat.accel == AccelKind::Hardware;
  bool shaded = scene.settings.mode != RenderMode::Binary && scene.settings.maxBounces > 0;
  for (const Shape& shape : scene.shapes) {
    const Material& material = scene.materials.at(shape.material);
    // A metal's texels may be smoother than their mean.
    bool texturedMetal = material.metalRoughTexture >= 0 && material.metallic > 0.0f;
    bool mirror = material.reflectivity > 0.0f || texturedMetal;
    features.reflection |= shaded && mirror;
    // glTF metals: highlights and mirrors take the base colour at the point
    // (a tint of mix(white, base, metallic), so only metals need it).
    features.tintedMirrors |= shaded && material.tintedMirror && material.metallic > 0.0f;
    features.refraction |= shaded && material.transmission > 0.0f;
    features.tintedTransmission |=
        shaded && material.transmission > 0.0f && material.tintedTransmission;
    features.thinWalls |= shaded && material.transmission > 0.0f && material.thinWalled;
  }
  features.vertices = !flat.vertices.empty();
  features.vertexColors = shaded && usesVertexColors(scene);
  for (const gpu::GpuMaterial& material : flat.materials) {
    features.normalMaps |= shaded && material.normalTexture >= 0;
    features.glow |= shaded && gpu::isGlowProfile(material.emissionProfile);
    features.metalRoughTextures |= shaded && material.metalRoughTexture >= 0;
    features.transmissionTextures |=
        shaded && material.transmission > 0.0f && material.transmissionTexture >= 0;
    features.textures |= shaded && samplesTextures(material);
  }
  // Cutouts read their alpha texture in every mode, binary's silhouettes too.
  if (features.alphaCutouts) {
    for (const gpu::GpuMaterial& material : flat.materials)
      features.textures |= hasAlphaCutout(material) && material.alphaTexture >= 0;
  }
  features.textureSamplers =
      features.textures && std::any_of(scene.textures.begin(), scene.textures.end(),
                                       [](const Texture& t) { return !t.sampling.isDefault(); });
  features.thinLens =
      scene.camera.type == CameraType::ThinLens && scene.camera.apertureRadius > 0.0f;
  bool lit = scene.settings.mode != RenderMode::Binary;
  features.areaLights = lit && !flat.areaLights.empty();
  if (features.areaLights) {
    for (const gpu::GpuEmitter& emitter : flat.emitters)
      features.emitterKinds |= 1u << emitter.kind;
    bool bounces =
        scene.settings.mode == RenderMode::PathTracer || flat.info.distributedBounces > 0;
    features.lightReplicas =
        lightReplicasFor(scene.settings, adaptive, bounces, flat.info.areaLightSamples);
  }
  // A walk pushes at most one entry per level of its path through both
  // levels, and the marker that ends a placed mesh.
  uint32_t deepestStack = flat.bvhDepth + (features.instanceTransforms ? 1u : 0u);
  features.stackInRegisters = deepestStack <= RT_BVH_STACK_REGISTERS;
  bool pairable = !features.hardwareAccel && !features.instanceTransforms;
  features.shadowPairs =
      pairable && lit &&
      flat.info.pointLightCount + features.lightReplicas * flat.info.areaLightSamples >= 2;
  features.primaryPairs = pairable && features.binaryOnly;
  features.pathTracer = scene.settings.mode == RenderMode::PathTracer;
  features.diffuseBounces =
      features.pathTracer ? scene.settings.maxBounces > 0 : lit && flat.info.distributedBounces > 0;
  if (features.pathTracer) {
    features.whittedStackSize = 1;  // one path: each hit follows one continuation
  } else if (features.diffuseBounces) {
    // Depth first, up to three continuations a hit: two pending rays per level.
    uint32_t levels = scene.settings.maxBounces + flat.info.distributedBounces;
    features.whittedStackSize = std::min(2 * levels + 1, kMaxWhittedStack);
  } else if (features.refraction) {
    // Depth-first walk of a binary ray tree: at most one pending ray per level.
    features.whittedStackSize = std::min(scene.settings.maxBounces + 1, kMaxWhittedStack);
  }
  // The path tracer already follows one continuation by weight.
  if (!features.pathTracer && (features.reflection || features.refraction)) {
    features.rouletteWeight = std::max(scene.settings.rouletteWeight, 0.0f);
  }
  return features;
}

ShaderDefines ShaderFeatures::defines() const {
  ShaderDefines result;
  auto flag = [&](bool on, const char* name) {
    if (on) result.emplace_back(name, "1");
  };
  flag(spheres, "RT_FEATURE_SPHERES");
  flag(triangles, "RT_FEATURE_TRIANGLES");
  flag(cylinders, "RT_FEATURE_CYLINDERS");
  flag(meshes, "RT_FEATURE_MESHES");
  flag(looseTriangles, "RT_FEATURE_LOOSE_TRIANGLES");
  flag(instanceTransforms, "RT_FEATURE_INSTANCE_TRANSFORMS");
  flag(reflection, "RT_FEATURE_REFLECTION");
  flag(refraction, "RT_FEATURE_REFRACTION");
  flag(thinLens, "RT_FEATURE_THIN_LENS");
  flag(vertices, "RT_FEATURE_VERTICES");
  flag(vertexColors, "RT_FEATURE_VERTEX_COLORS");
  flag(textures, "RT_FEATURE_TEXTURES");
  flag(normalMaps, "RT_FEATURE_NORMAL_MAPS");
  flag(glow, "RT_FEATURE_GLOW");
  flag(metalRoughTextures, "RT_FEATURE_METAL_ROUGH_TEXTURES");
  flag(tintedMirrors, "RT_FEATURE_TINTED_MIRRORS");
  flag(tintedTransmission, "RT_FEATURE_TINTED_TRANSMISSION");
  flag(thinWalls, "RT_FEATURE_THIN_WALLS");
  flag(transmissionTextures, "RT_FEATURE_TRANSMISSION_TEXTURES");
  flag(alphaCutouts, "RT_FEATURE_ALPHA_CUTOUTS");
  flag(textureSamplers, "RT_FEATURE_TEXTURE_SAMPLERS");
  flag(areaLights, "RT_FEATURE_AREA_LIGHTS");
  flag(diffuseBounces, "RT_FEATURE_DIFFUSE_BOUNCES");
  flag(pathTracer, "RT_FEATURE_PATH_TRACER");
  flag(countRays, "RT_COUNT_RAYS");
  flag(countRaysPerSubgroup, "RT_COUNT_RAYS_PER_SUBGROUP");
  flag(oddSums, "RT_ODD_SUMS");
  flag(adaptiveSampling, "RT_ADAPTIVE_SAMPLING");
  flag(hardwareAccel, "RT_ACCEL_HARDWARE");
  flag(storageBuffers, "RT_SCENE_STORAGE_BUFFERS");
  flag(binaryOnly, "RT_BINARY_ONLY");
  flag(shadowPairs, "RT_SHADOW_PAIRS");
  flag(primaryPairs, "RT_PRIMARY_PAIRS");
  flag(workQueue, "RT_WORK_QUEUE");
  flag(laneVotes, "RT_LANE_VOTES");
  flag(stackInRegisters, "RT_BVH_STACK_IN_REGISTERS");
  if (samplerKind >= 0) result.emplace_back("RT_SAMPLER_KIND", std::to_string(samplerKind) + "u");
  if (emitterKinds != 0) {
    result.emplace_back("RT_EMITTER_KINDS", std::to_string(emitterKinds) + "u");
  }
  result.emplace_back("RT_WHITTED_STACK_SIZE", std::to_string(whittedStackSize));
  if (lightReplicas > 1)
    result.emplace_back("RT_LIGHT_REPLICAS", std::to_string(lightReplicas) + "u");
  if (rouletteWeight > 0.0f) {
    result.emplace_back("RT_ROULETTE_WEIGHT", fmt::format("{:.9g}", rouletteWeight));
  }
  return result;
}

std::string ShaderFeatures::summary() const {
  std::string text;
  for (const auto& [name, value] : defines()) {
    if (name.rfind("RT_FEATURE_", 0) != 0) continue;
    text += (text.empty() ? "" : " ") + lowercase(name.substr(11));
  }
  if (lightReplicas > 1) text += fmt::format(" light_split({})", lightReplicas);
  return text.empty() ? "none" : text;
}

}  // namespace rt
