#version 460
// Test kernel: writes samplePair() of consecutive sample indices (or
// sampleSubPair() of each pixel sample's sub-points in turn), so the tests
// can check the samplers of shaders/rng.glsl directly.
#extension GL_GOOGLE_include_directive : require

#include "gpu_types.h"

layout(local_size_x = 64) in;

layout(push_constant) uniform ProbeParams {
  uint samplerKind;
  uint pixel;
  uint firstSample;
  uint count;
  uint samplesTotal;
  uint dimension;
  uint seed;
  uint subCount;  // points per pixel sample (sampleSubPair); 0 or 1: samplePair
}
params;

layout(std430, set = 0, binding = 0) buffer Points { vec2 points[]; };

#include "rng.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  if (params.subCount <= 1u) {
    points[i] = samplePair(params.samplerKind, params.pixel, params.firstSample + i,
                           params.samplesTotal, params.dimension, params.seed);
  } else {
    points[i] = sampleSubPair(params.samplerKind, params.pixel,
                              params.firstSample + i / params.subCount, i % params.subCount,
                              params.subCount, params.samplesTotal, params.dimension, params.seed);
  }
}
