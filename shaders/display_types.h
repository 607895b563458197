// Structures the viewer's display pass shares with shaders/display.comp.
// Same rules as gpu_types.h: std430, sizes checked at compile time.
#ifndef RT_DISPLAY_TYPES_H
#define RT_DISPLAY_TYPES_H

#include "tone_mapping.h"

#ifdef __cplusplus
namespace rt::gpu {
#endif

// Descriptor set 0 of the display kernel.
#define RT_DISPLAY_BINDING_ACCUMULATION 0  // vec4 per pixel: rgb sum, a = sample count
#define RT_DISPLAY_BINDING_PIXELS 1        // uint per pixel: 8-bit r, g, b, a from the low byte

#define RT_DISPLAY_WORKGROUP_SIZE 16  // 16 x 16: measured faster than 8 x 8 on lavapipe

// Push constants of one display dispatch.
struct GpuDisplayParams {
  uvec2 size;       // accumulation (and display image) size in pixels
  float exposure;   // linear scale before the curve, as rt::toneMappingFor
  uint firstRow;    // the dispatch covers rows firstRow.. (those that got samples)
  uint truncate;    // 1: bytes are floor(255 v) (rt::Quantization::Truncate); 0: rounded
  uint srgbEncode;  // 1: the sRGB transfer function after the curve (rt::ToneMapping)
  uint toneCurve;   // RT_TONE_CURVE_* (tone_mapping.h)
  uint pad2;
};
RT_ASSERT_STD430_SIZE(GpuDisplayParams, 32);

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_DISPLAY_TYPES_H
