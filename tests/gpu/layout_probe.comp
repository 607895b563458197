#version 460
// Reads record 0 of one scene array (or the frame's push constants) through
// the shaders' own reader and stores it as a std430 struct, so that the host
// can compare it word by word with what it uploaded (test_gpu_layout.cpp).
// RT_PROBE_TYPE names the struct, RT_PROBE_READ the expression that loads it.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 1) in;

#include "gpu_types.h"
#include "bindings.glsl"
#include "frame.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "textures.glsl"

layout(std430, set = 0, binding = RT_BINDING_HITS) buffer ProbeOutput { RT_PROBE_TYPE probed; };

// emitterCdfEnd reads one field on its own (the area light's piece search):
// it must find the word loadEmitter takes cdfEnd from.
GpuEmitter emitterThroughCdfEnd(uint index) {
  GpuEmitter emitter = loadEmitter(index);
  emitter.cdfEnd = emitterCdfEnd(index);
  return emitter;
}

void main() {
  loadSceneInfo();
  loadFrameParams();
  probed = RT_PROBE_READ;
}
