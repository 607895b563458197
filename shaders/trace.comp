#version 460
// Render kernel: each invocation adds `sampleCount` samples to one pixel's
// float32 accumulator. Feature defines (RT_FEATURE_*) are set per scene by
// the host so that unused code is never compiled.
#extension GL_GOOGLE_include_directive : require
#ifdef RT_COUNT_RAYS_PER_SUBGROUP
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#ifdef RT_WORK_QUEUE
#extension GL_KHR_shader_subgroup_ballot : require
#endif

#include "gpu_types.h"

layout(local_size_x = RT_WORKGROUP_SIZE_X, local_size_y = RT_WORKGROUP_SIZE_Y) in;

// One vec4 per pixel. Storage buffers, not storage texel buffers: each
// invocation loads and stores its pixel once a pass, and on Mesa 25's
// lavapipe a texel buffer's imageStore cost about 15 ns of wall time a pixel
// (2 cores) against 3-7 ns for a storage buffer's store, which made a pass of
// one sample over a 2048x2048 image with an empty sample loop 1.7x slower
// (bench/README.md).
layout(std430, set = 0, binding = RT_BINDING_ACCUMULATION) restrict buffer AccumulationBuffer {
  vec4 accumulation[];  // rgb: sum of sample radiance, a: number of samples
};
#ifdef RT_ODD_SUMS
// Only where an error estimate reads them (ProgressiveOptions::oddSums): the
// second load and store a pixel and pass made a one-sample render of the
// official binary_primitves.json 1.24x slower (bench/README.md).
layout(std430, set = 0, binding = RT_BINDING_ACCUMULATION_ODD) restrict buffer
    OddAccumulationBuffer {
  vec4 oddAccumulation[];  // the same over odd sample indices only
};
#endif

#ifdef RT_ADAPTIVE_SAMPLING
// Per tile of RT_ADAPTIVE_TILE_SIZE^2 pixels, row-major over the whole
// image: (first sample index, sample count) of this dispatch.
layout(std430, set = 0, binding = RT_BINDING_SAMPLE_PLAN) restrict readonly buffer SamplePlanBuffer {
  uvec2 samplePlan[];
};
layout(std430, set = 0, binding = RT_BINDING_TILE_RAYS) restrict buffer TileRaysBuffer {
  uint tileRays[];
};
layout(std430, set = 0, binding = RT_BINDING_PIXEL_EXTRAS) restrict readonly buffer PixelExtrasBuffer {
  uint pixelExtras[];
};

// This dispatch's (first sample index, count) of the pixel from its tile's
// plan: the paired pixels' extra first-round sample (RT_ADAPTIVE_PAIRED_FLAG)
// and the edge round's per-pixel samples (RT_ADAPTIVE_EXTRAS_FLAG).
uvec2 plannedRange(uvec2 planned, uvec2 pixel, uint pixelIndex) {
  uint paired = adaptivePairedPixel(pixel.x, pixel.y);
  bool extras = ((planned.x | planned.y) & RT_ADAPTIVE_EXTRAS_FLAG) != 0u;
  uint extra = extras ? pixelExtras[pixelIndex] : 0u;
  uvec2 range = (planned & ~RT_ADAPTIVE_PLAN_FLAGS) + (planned >> 31u) * paired;
  return range + ((planned >> 30u) & 1u) * extra;
}
#endif

#ifdef RT_COUNT_RAYS
layout(std430, set = 0, binding = RT_BINDING_RAY_COUNTER) buffer RayCounterBuffer {
  uint rayCounter[];
};
#endif

#ifdef RT_WORK_QUEUE
// Runs of pixels taken so far in this dispatch (zeroed before it).
layout(std430, set = 0, binding = RT_BINDING_WORK_QUEUE) restrict buffer WorkQueueBuffer {
  uint runsTaken;
};
#endif

// Each file includes what it uses (include guards keep one copy).
#include "binary.glsl"
#include "camera.glsl"
#include "frame.glsl"
#include "geometry.glsl"
#include "integrator.glsl"

// The pixel of invocation `index` in its 8x8 group: each run of eight
// invocations (one SIMD vector on lavapipe, a quarter of a 32-wide GPU
// wave) takes a 4x2 block rather than a row of eight, so its rays stay
// closer together and walk more of the same BVH nodes: 1.03-1.08x on the
// common scene and the thin-lens study (bench/README.md). The image does
// not change: every pixel is still computed by itself.
#if RT_WORKGROUP_SIZE_X != 8 || RT_WORKGROUP_SIZE_Y != 8
#error pixelInGroup lays out 8x8 groups
#endif
uvec2 pixelInGroup(uint index) {
  uint lane = index & 7u, run = index >> 3u;
  return uvec2((run & 1u) * 4u + (lane & 3u), (run >> 1u) * 2u + (lane >> 2u));
}

// The camera ray of sample s of a pixel.
Ray sampleRay(uvec2 pixel, uint pixelIndex, uint s) {
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
  return cameraRay(vec2(pixel) + jitter, lens);
}

// Adds sample s's value to the pixel's sums (the odd samples' too).
void addSample(inout vec4 sum, inout vec4 oddSum, uint s, vec3 radiance) {
  vec4 contribution = vec4(finiteOrZero(radiance), 1.0);
  sum += contribution;
#ifdef RT_ODD_SUMS
  if ((s & 1u) == 1u) oddSum += contribution;
#endif
}

// Adds this dispatch's samples to the pixel of invocation `index` (0..63) of
// 8x8 block `group` of the tile.
void renderPixel(uvec2 group, uint index) {
  uvec2 local = group * gl_WorkGroupSize.xy + pixelInGroup(index);
  if (any(greaterThanEqual(local, frame.tileSize))) return;
  uvec2 pixel = frame.tileOrigin + local;
  uint pixelIndex = pixel.y * sceneInfo.width + pixel.x;
#ifdef RT_ADAPTIVE_SAMPLING
  uint raysBefore = raysTraced;
  uint tilesPerRow = adaptiveTileGrid(uvec2(sceneInfo.width, 0u)).x;
  uint tile = (pixel.y / RT_ADAPTIVE_TILE_SIZE) * tilesPerRow + pixel.x / RT_ADAPTIVE_TILE_SIZE;
  uvec2 range = plannedRange(samplePlan[tile], pixel, pixelIndex);
  if (range.y == 0u) return;
#else
  uvec2 range = uvec2(frame.sampleBegin, frame.sampleCount);
#endif
  // Samples are added one by one in index order, so the sum is the same
  // however the sample range is split over dispatches.
  vec4 sum = accumulation[pixelIndex];
#ifdef RT_ODD_SUMS
  vec4 oddSum = oddAccumulation[pixelIndex];
#else
  vec4 oddSum = vec4(0.0);  // not kept
#endif
  uint end = range.x + range.y;
#ifdef RT_PRIMARY_PAIRS
  // Two samples at a time, their primary rays walked together: the bunny's
  // primary rays 1.11x (bench/README.md).
  for (uint s = range.x; s < end; s += 2u) {
    bool hasSecond = s + 1u < end;
    Ray first = sampleRay(pixel, pixelIndex, s);
    Ray second = first;
    if (hasSecond) second = sampleRay(pixel, pixelIndex, s + 1u);
    vec3 firstValue;
    vec3 secondValue;
    binaryRadiancePair(first, second, hasSecond, firstValue, secondValue);
    addSample(sum, oddSum, s, firstValue);
    if (hasSecond) addSample(sum, oddSum, s + 1u, secondValue);
  }
#else
  for (uint s = range.x; s < end; ++s) {
    Ray ray = sampleRay(pixel, pixelIndex, s);
#ifdef RT_BINARY_ONLY
    vec3 radiance = binaryRadiance(ray);
#else
    vec3 radiance = traceRadiance(ray, uvec2(pixelIndex, s));
#endif
    addSample(sum, oddSum, s, radiance);
  }
#endif
  accumulation[pixelIndex] = sum;
#ifdef RT_ODD_SUMS
  oddAccumulation[pixelIndex] = oddSum;
#endif
#ifdef RT_ADAPTIVE_SAMPLING
  // Integer sums: the same whatever order the invocations add in.
  atomicAdd(tileRays[tile], raysTraced - raysBefore);
#endif
}

void main() {
  loadSceneInfo();
  loadFrameParams();
#ifdef RT_WORK_QUEUE
  // CPU drivers split a dispatch's workgroups into one contiguous share per
  // worker thread (lavapipe: groups / threads each), so a thread whose share
  // holds the glass waits while the other idles at the end of every
  // dispatch. Here each subgroup takes the next run of pixels from a counter
  // until none is left: the threads finish within one run of each other.
  // A run is gl_SubgroupSize consecutive invocations of the grid's 8x8
  // blocks in row order, laid out as a workgroup's would be.
  uvec2 groups = (frame.tileSize + gl_WorkGroupSize.xy - 1u) / gl_WorkGroupSize.xy;
  uint invocationsPerGroup = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
  uint runs = groups.x * groups.y * (invocationsPerGroup / gl_SubgroupSize);
  for (;;) {
    uint run = 0u;
    if (subgroupElect()) run = atomicAdd(runsTaken, 1u);
    run = subgroupBroadcastFirst(run);
    if (run >= runs) break;
    uint invocation = run * gl_SubgroupSize + gl_SubgroupInvocationID;
    uint group = invocation / invocationsPerGroup;
    renderPixel(uvec2(group % groups.x, group / groups.x), invocation % invocationsPerGroup);
  }
#else
  // The block this workgroup renders (see GpuFrameParams::groupStride).
  renderPixel((gl_WorkGroupID.xy * frame.groupStride) % gl_NumWorkGroups.xy,
              gl_LocalInvocationIndex);
#endif
#ifdef RT_COUNT_RAYS
#ifdef RT_COUNT_RAYS_PER_SUBGROUP
  // Every lane's atomic add to the one counter contends across the driver's
  // threads: on lavapipe, one add a subgroup made the bunny bench's primary
  // rays about 3% faster (five interleaved runs, 0-8%).
  uint subgroupRays = subgroupAdd(raysTraced);
  if (subgroupElect()) atomicAdd(rayCounter[0], subgroupRays);
#else
  atomicAdd(rayCounter[0], raysTraced);
#endif
#endif
}
