#version 460
// Viewer display pass: turns the renderer's float32 accumulation buffer into
// the 8-bit pixels shown in the window, with the same tone mapping as the PNG
// writer (exposure, tone curve (a clamp to [0, 1] by default), sRGB encoding when asked, rounded or truncated to 1/255),
// so a screenshot of the window equals the offline render.
// The pixels go to a buffer in RGBA8 memory order, which the host copies into
// an RGBA8 image: on lavapipe, imageStore to an rgba8 image costs about three
// times as much as this whole pass.
#extension GL_GOOGLE_include_directive : require

#include "display_types.h"

layout(local_size_x = RT_DISPLAY_WORKGROUP_SIZE, local_size_y = RT_DISPLAY_WORKGROUP_SIZE) in;

layout(push_constant) uniform DisplayParamsBlock { GpuDisplayParams params; };

layout(std430, set = 0, binding = RT_DISPLAY_BINDING_ACCUMULATION) readonly buffer Accumulation {
  vec4 accumulation[];
};
layout(std430, set = 0, binding = RT_DISPLAY_BINDING_PIXELS) writeonly buffer Pixels {
  uint pixels[];
};

// rt::toneMap's quantize(displayValue(v)).
uint toneMapChannel(float value) {
  float unit = displayChannel(value, params.exposure, params.toneCurve, params.srgbEncode);
  return uint(floor(unit * 255.0 + (params.truncate != 0u ? 0.0 : 0.5)));
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy + uvec2(0, params.firstRow);
  if (any(greaterThanEqual(pixel, params.size))) return;
  uint index = pixel.y * params.size.x + pixel.x;
  vec4 sum = accumulation[index];
  // A pixel without samples yet (right after a restart) keeps what the image
  // showed before, so a new view wipes over the old one band by band.
  if (sum.a <= 0.0) return;
  vec3 mean = sum.rgb / sum.a;
  pixels[index] = toneMapChannel(mean.r) | (toneMapChannel(mean.g) << 8) |
                  (toneMapChannel(mean.b) << 16) | (255u << 24);
}
