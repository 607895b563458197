// glTF's metallic-roughness onto the renderer's Blinn-Phong terms: one
// definition for the glTF loader (a material's factors, src/formats/gltf)
// and the kernels (each texel of a metallic-roughness texture,
// textures.glsl's applyMetalRough), so that a texture of one value renders
// as its factors would. m = metallic, r = roughness, t = transmission:
//   kd               = (1 - m) (1 - t)           metals and glass have no diffuse term
//   specularColor    = mix(white, baseColor, m)   metals tint their highlights
//   specularExponent = clamp(2 / r^4 - 2, 1, 10000): the Blinn-Phong lobe as wide as the
//                      microfacet lobe of roughness r (alpha = r^2; Walter et al. 2007)
//   ks               = min(1, F0 (p + 8) / (8 pi)),  F0 = mix(0.04, 1, m): the peak of the
//                      energy-normalised Blinn-Phong lobe with the Fresnel reflectance at
//                      normal incidence, capped at 1 (images are clamped anyway)
//   reflectivity     = m (1 - r)^2                mirror reflection of smooth metals,
//                      tinted by specularColor (GpuMaterial::flags)
#ifndef RT_METAL_ROUGH_H
#define RT_METAL_ROUGH_H

#include "gpu_types.h"

#ifdef __cplusplus
#include <algorithm>
namespace rt::gpu {
using std::clamp;
using std::min;
#endif

// Blinn-Phong exponents beyond this are a mirror in all but name.
#define RT_MAX_SPECULAR_EXPONENT 10000.0f

RT_SHARED_FUNCTION float metalRoughKd(float metallic, float transmission) {
  return (1.0f - metallic) * (1.0f - transmission);
}

RT_SHARED_FUNCTION float metalRoughExponent(float roughness) {
  float r4 = roughness * roughness * roughness * roughness;
  return r4 > 2.0f / RT_MAX_SPECULAR_EXPONENT
             ? clamp(2.0f / r4 - 2.0f, 1.0f, RT_MAX_SPECULAR_EXPONENT)
             : RT_MAX_SPECULAR_EXPONENT;
}

RT_SHARED_FUNCTION float metalRoughKs(float metallic, float exponent) {
  float f0 = 0.04f + 0.96f * metallic;
  return min(1.0f, f0 * (exponent + 8.0f) / (8.0f * 3.14159265f));
}

RT_SHARED_FUNCTION float metalRoughReflectivity(float metallic, float roughness) {
  return metallic * (1.0f - roughness) * (1.0f - roughness);
}

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_METAL_ROUGH_H
