#version 460
// Render kernel: each invocation adds `sampleCount` samples to one pixel's
// float32 accumulator. Feature defines (RT_FEATURE_*) are set per scene by
// the host so that unused code is never compiled.
#extension GL_GOOGLE_include_directive : require

#include "gpu_types.h"

layout(local_size_x = RT_WORKGROUP_SIZE_X, local_size_y = RT_WORKGROUP_SIZE_Y) in;

layout(push_constant) uniform FrameParamsBlock { GpuFrameParams frameBlock; };
// frameBlock through opaqueZero() (see bindings.glsl), set first in main().
GpuFrameParams frame;

// Storage texel buffers (one RGBA32F texel per pixel): CPU drivers read a
// storage buffer lane by lane, an image with one gather.
layout(rgba32f, set = 0, binding = RT_BINDING_ACCUMULATION) uniform restrict imageBuffer
    accumulation;  // rgb: sum of sample radiance, a: number of samples
layout(rgba32f, set = 0, binding = RT_BINDING_ACCUMULATION_ODD) uniform restrict imageBuffer
    oddAccumulation;  // the same over odd sample indices only

#ifdef RT_COUNT_RAYS
layout(std430, set = 0, binding = RT_BINDING_RAY_COUNTER) buffer RayCounterBuffer {
  uint rayCounter[];
};
#endif

#include "bindings.glsl"
#include "rng.glsl"
#include "intersect.glsl"
#include "traverse.glsl"
#include "geometry.glsl"
#include "surface.glsl"
#include "textures.glsl"
#include "camera.glsl"
#include "optics.glsl"
#include "lights.glsl"
#include "shading.glsl"
#include "integrator.glsl"
#include "binary.glsl"

void loadFrameParams() {
  uint z = opaqueZero();
  GpuFrameParams b = frameBlock;
  frame = GpuFrameParams(opaqueUint(b.tileOrigin, z), opaqueUint(b.tileSize, z),
                         opaqueUint(b.groupStride, z), opaqueUint(b.sampleBegin, z),
                         opaqueUint(b.sampleCount, z), opaqueUint(b.samplesTotal, z),
                         opaqueUint(b.seed, z), opaqueUint(b.samplerKind, z), 0u);
}

void main() {
  loadSceneInfo();
  loadFrameParams();
  // The block this workgroup renders (see GpuFrameParams::groupStride).
  uvec2 group = (gl_WorkGroupID.xy * frame.groupStride) % gl_NumWorkGroups.xy;
  uvec2 local = group * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
  if (any(greaterThanEqual(local, frame.tileSize))) return;
  uvec2 pixel = frame.tileOrigin + local;
  uint pixelIndex = pixel.y * sceneInfo.width + pixel.x;
  // Samples are added one by one in index order, so the sum is the same
  // however the sample range is split over dispatches.
  vec4 sum = imageLoad(accumulation, int(pixelIndex));
  vec4 oddSum = imageLoad(oddAccumulation, int(pixelIndex));
  for (uint s = frame.sampleBegin; s < frame.sampleBegin + frame.sampleCount; ++s) {
    vec2 jitter = samplePair(frame.samplerKind, pixelIndex, s, frame.samplesTotal, RT_DIM_PIXEL,
                             frame.seed);
#ifdef RT_FEATURE_THIN_LENS
    vec2 lens = samplePair(frame.samplerKind, pixelIndex, s, frame.samplesTotal, RT_DIM_LENS,
                           frame.seed);
#else
    // A pinhole needs no lens point; the compiler keeps the sampler's loops
    // even when their result is unused, so it is not drawn at all.
    const vec2 lens = vec2(0.5);
#endif
    Ray ray = cameraRay(vec2(pixel) + jitter, lens);
#ifdef RT_BINARY_ONLY
    vec3 radiance = binaryRadiance(ray);
#else
    vec3 radiance = traceRadiance(ray, uvec2(pixelIndex, s));
#endif
    vec4 contribution = vec4(finiteOrZero(radiance), 1.0);
    sum += contribution;
    if ((s & 1u) == 1u) oddSum += contribution;
  }
  imageStore(accumulation, int(pixelIndex), sum);
  imageStore(oddAccumulation, int(pixelIndex), oddSum);
#ifdef RT_COUNT_RAYS
  atomicAdd(rayCounter[0], raysTraced);
#endif
}
