// The render kernel's per-dispatch parameters (push constants, GpuFrameParams):
// which tile and samples a dispatch adds, and with which sampler and seed.
#ifndef RT_FRAME_GLSL
#define RT_FRAME_GLSL

#include "gpu_types.h"
#include "bindings.glsl"

layout(push_constant) uniform FrameParamsBlock { GpuFrameParams frameBlock; };
// frameBlock through opaqueZero() (see bindings.glsl), set first in main().
GpuFrameParams frame;

void loadFrameParams() {
  uint z = opaqueZero();
  GpuFrameParams b = frameBlock;
  frame = GpuFrameParams(opaqueUint(b.tileOrigin, z), opaqueUint(b.tileSize, z),
                         opaqueUint(b.groupStride, z), opaqueUint(b.sampleBegin, z),
                         opaqueUint(b.sampleCount, z), opaqueUint(b.samplesTotal, z),
                         opaqueUint(b.seed, z), opaqueUint(b.samplerKind, z), 0u);
}

#endif
