#version 460
// Viewer display pass: turns the renderer's float32 accumulation buffer into
// the 8-bit image shown in the window, with the same tone mapping as the PNG
// writer (exposure, clamp to [0, 1], no gamma, round to the nearest 1/255), so
// a screenshot of the window equals the offline render.
#extension GL_GOOGLE_include_directive : require

#include "display_types.h"

layout(local_size_x = RT_DISPLAY_WORKGROUP_SIZE, local_size_y = RT_DISPLAY_WORKGROUP_SIZE) in;

layout(push_constant) uniform DisplayParamsBlock { GpuDisplayParams params; };

layout(std430, set = 0, binding = RT_DISPLAY_BINDING_ACCUMULATION) readonly buffer Accumulation {
  vec4 accumulation[];
};
layout(set = 0, binding = RT_DISPLAY_BINDING_IMAGE, rgba8) uniform writeonly image2D displayImage;

// rt::toneMap's quantize(applyCurve(v * exposure)): NaN and negatives go to 0.
float toneMapChannel(float value) {
  float exposed = value * params.exposure;
  float unit = exposed > 0.0 ? min(exposed, 1.0) : 0.0;
  return floor(unit * 255.0 + 0.5) / 255.0;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, params.size))) return;
  vec4 sum = accumulation[pixel.y * params.size.x + pixel.x];
  // A pixel without samples yet (right after a restart) keeps what the image
  // showed before, so a new view wipes over the old one band by band.
  if (sum.a <= 0.0) return;
  vec3 mean = sum.rgb / sum.a;
  vec3 display = vec3(toneMapChannel(mean.r), toneMapChannel(mean.g), toneMapChannel(mean.b));
  imageStore(displayImage, ivec2(pixel), vec4(display, 1.0));
}
