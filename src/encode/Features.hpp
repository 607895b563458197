// Which shader code a scene needs. Each feature becomes an RT_FEATURE_*
// define, so a scene without (say) refraction never compiles or runs the
// refraction code (the Mitsuba "variants" idea, chosen per scene at run time).
#pragma once

#include <cstdint>
#include <string>

#include "encode/FlatScene.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "scene/Scene.hpp"

namespace rt {

// How rays that start together walk the BVH: two by two (the default: a
// shading point's shadow rays where a scene has two or more light samples a
// hit, and binary mode's primary rays two samples of a pixel at a time), or
// one by one (to measure other GPUs). The image is the same.
enum class Walks { Paired, Single };

// How a render dispatch's pixels reach the driver's threads: on CPU devices
// each subgroup takes the next run of pixels from a queue (the default),
// or, as on GPUs, each workgroup renders its own block of the grid. The
// image is the same.
enum class WorkQueue { OnCpu, Off };

struct ShaderFeatures {
  bool spheres = false;
  bool triangles = false;       // also quads and meshes
  bool meshes = false;          // mesh instances: the two-level BVH
  bool looseTriangles = false;  // triangles and quads that are top-level items, not in a mesh
  // Some mesh instance is not in world space (a mesh placed more than once):
  // the walk moves the ray into it.
  bool instanceTransforms = false;
  bool cylinders = false;
  bool reflection = false;
  bool refraction = false;
  bool thinLens = false;
  bool vertices = false;      // per-vertex normals / UVs on triangles
  bool vertexColors = false;  // some shaded mesh has vertex colours
  bool textures = false;
  bool normalMaps = false;          // some shaded material has a normal map (needs textures)
  bool glow = false;                // some shaded material glows (RT_EMISSION_GLOW, _UNLIT)
  bool metalRoughTextures = false;  // some shaded material has a metallic-roughness texture
  // Some shaded glTF metal: its highlights and mirror reflections take the
  // base colour at the point (GpuMaterial::flags).
  bool tintedMirrors = false;
  // Some shaded glTF glass: light through it, shadow rays' included, takes
  // its base colour (GpuMaterial::flags).
  bool tintedTransmission = false;
  // Some shaded glass is a thin wall (GpuMaterial::flags): its light does not bend.
  bool thinWalls = false;
  // Some shaded glass has a transmission texture (GpuMaterial::transmissionTexture).
  bool transmissionTextures = false;
  // Some mesh instance's material cuts holes (RT_PRIM_ALPHA_CUTOUT): the
  // walks ask about each hit on it (shaders/alpha.glsl).
  bool alphaCutouts = false;
  // Some texture is not read bilinearly with repeat wrapping (glTF samplers:
  // clamp, mirror, nearest; TextureSampling).
  bool textureSamplers = false;
  bool areaLights = false;
  bool diffuseBounces = false;        // sampled diffuse bounces (distributed bounces, path tracer)
  bool pathTracer = false;            // one continuation per hit
  bool countRays = false;             // benchmark instrumentation
  bool countRaysPerSubgroup = false;  // with countRays: one atomic add a subgroup
  bool oddSums = false;               // the odd samples' sums too (error estimates)
  bool adaptiveSampling = false;      // per-tile sample ranges (render/AdaptiveSampling.hpp)
  bool hardwareAccel = false;         // ray queries instead of the BVH walk (--accel hardware)
  // The scene arrays are storage buffers, not texel buffers (SceneArrays).
  bool storageBuffers = false;
  // Binary mode: a sample is one closest-hit query; no shading code is built.
  bool binaryOnly = false;
  // The pixel sampler (RT_SAMPLER_*) when one is fixed for the kernel's life,
  // so only its code is built; -1: chosen per dispatch (samplerKind).
  int samplerKind = -1;
  // Kinds of area-light pieces (bits 1 << RT_PRIM_*), so that only their
  // sampling code is built; 0: no area lights.
  uint32_t emitterKinds = 0;
  // Pending rays of the ray tree.
  uint32_t whittedStackSize = 1;
  // RenderSettings::rouletteWeight where the tree branches.
  float rouletteWeight = 0.0f;
  // Replicas of a hit's area-light estimate (RenderSettings::lightSplit, or
  // the automatic choice of lightReplicasFor in Features.cpp; 1: off).
  uint32_t lightReplicas = 1;
  // Rays walked two by two (traversePair in shaders/traverse_bvh.glsl),
  // through the renderer's own BVH, without instance transforms: a shading
  // point's shadow rays where a hit has two or more light samples, and
  // binary mode's primary rays, two samples of a pixel at a time.
  bool shadowPairs = false;
  bool primaryPairs = false;
  // Subgroups take runs of pixels from a queue (WorkQueue; trace.comp).
  bool workQueue = false;
  // Every walk's stack fits the entries held in registers
  // (RT_BVH_STACK_REGISTERS): the walk is built without the stack's array.
  bool stackInRegisters = false;
  // The BVH walk writes its stack's array only where some lane of the
  // subgroup must (subgroupAny; shaders/traverse_bvh.glsl): the device has
  // subgroup votes.
  bool laneVotes = false;

  ShaderDefines defines() const;
  std::string summary() const;  // e.g. "spheres triangles reflection"
};

// `flat` is the scene flattened for the GPU (it knows which triangles carry
// vertex data and which textures are drawn).
// `adaptive`: for adaptive sampling (render/AdaptiveSampling.hpp), which
// splits the light automatically.
ShaderFeatures detectFeatures(const Scene& scene, const FlatScene& flat, bool adaptive = false);

}  // namespace rt
