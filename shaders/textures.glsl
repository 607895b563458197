// Diffuse colour of a material at a surface point: its texture, bilinearly
// filtered with repeat wrapping and decoded from sRGB, or its plain colour;
// a texture's alpha (coverage) for alpha cutouts.
#ifndef RT_TEXTURES_GLSL
#define RT_TEXTURES_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "metal_rough.h"
#include "tone_mapping.h"

#ifdef RT_FEATURE_TEXTURES
// The table (uint rows, one GpuTextureInfo a row) and every texture's
// texels (uints, each a packed RGBA8 sRGB-encoded texel); bindings.glsl.
RT_UINT_ROWS(RT_BINDING_TEXTURE_INFO, textureInfoTexels)
RT_UINT_WORDS(RT_BINDING_TEXELS, textureTexels)

GpuTextureInfo loadTextureInfo(int index) {
  uvec4 info = RT_ROW(textureInfoTexels, index * int(RT_TEXELS_PER_TEXTURE_INFO));
  return GpuTextureInfo(info.x, info.y, info.z, info.w);
}

uint textureTexel(uint index) { return RT_WORD(textureTexels, index); }

vec3 srgbToLinear(vec3 c) {
  return vec3(linearFromSrgb(c.r), linearFromSrgb(c.g), linearFromSrgb(c.b));
}

// Repeat wrapping of a texel coordinate in [-size, 2 size): what
// ((x % size) + size) % size gives, without integer division (CPU drivers
// divide vectors one lane at a time). sampleTexture's coordinates are in
// [-1, size]; anything else (NaN texture coordinates) stays inside the
// texture.
uint wrapTexel(int x, int size) {
  x = x < 0 ? x + size : x;
  x = x >= size ? x - size : x;
  return uint(clamp(x, 0, size - 1));
}

vec3 fetchTexel(GpuTextureInfo info, int x, int y) {
  uint tx = wrapTexel(x, int(info.width));
  uint ty = wrapTexel(y, int(info.height));
  vec3 texel = unpackUnorm4x8(textureTexel(info.firstTexel + ty * info.width + tx)).rgb;
#if defined(RT_FEATURE_NORMAL_MAPS) || defined(RT_FEATURE_METAL_ROUGH_TEXTURES)
  if (info.linear != 0u) return texel;  // data, not colours
#endif
  return srgbToLinear(texel);
}

// Alpha is coverage, stored linearly in sRGB images too.
float fetchTexelAlpha(GpuTextureInfo info, int x, int y) {
  uint tx = wrapTexel(x, int(info.width));
  uint ty = wrapTexel(y, int(info.height));
  return unpackUnorm4x8(textureTexel(info.firstTexel + ty * info.width + tx)).a;
}

// Bilinear filtering at `uv`: the texel (x, y) at the top left of the four
// around it, and the weights f of its right and lower neighbours.
struct BilinearTaps {
  int x;
  int y;
  vec2 f;
};

BilinearTaps bilinearTaps(GpuTextureInfo info, vec2 uv) {
  // Keep coordinates small before scaling so float precision holds far from 0.
  vec2 wrapped = uv - floor(uv);
  vec2 pixel = wrapped * vec2(info.width, info.height) - 0.5;
  vec2 base = floor(pixel);
  return BilinearTaps(int(base.x), int(base.y), pixel - base);
}

vec3 sampleTexture(int index, vec2 uv) {
  GpuTextureInfo info = loadTextureInfo(index);
  BilinearTaps at = bilinearTaps(info, uv);
  vec3 top = mix(fetchTexel(info, at.x, at.y), fetchTexel(info, at.x + 1, at.y), at.f.x);
  vec3 bottom =
      mix(fetchTexel(info, at.x, at.y + 1), fetchTexel(info, at.x + 1, at.y + 1), at.f.x);
  return mix(top, bottom, at.f.y);
}

float sampleTextureAlpha(int index, vec2 uv) {
  GpuTextureInfo info = loadTextureInfo(index);
  BilinearTaps at = bilinearTaps(info, uv);
  float top =
      mix(fetchTexelAlpha(info, at.x, at.y), fetchTexelAlpha(info, at.x + 1, at.y), at.f.x);
  float bottom = mix(fetchTexelAlpha(info, at.x, at.y + 1),
                     fetchTexelAlpha(info, at.x + 1, at.y + 1), at.f.x);
  return mix(top, bottom, at.f.y);
}
#endif

#if defined(RT_FEATURE_METAL_ROUGH_TEXTURES) || defined(RT_FEATURE_TINTED_MIRRORS)
// A glTF material at a surface point whose base colour (texture, factor and
// vertex colour) is `baseColor`: with a metallic-roughness texture, its
// texel (blue metallic, green roughness) times the factors as Blinn-Phong
// terms (metal_rough.h, the glTF loader's conversion); with a tinted mirror,
// the specular colour that tints highlights and reflections, mix(white,
// baseColor, metallic) (the host has only the base colour factor).
void applyMetalRough(inout GpuMaterial material, vec2 uv, vec3 baseColor) {
  float m = material.metallic;
#ifdef RT_FEATURE_METAL_ROUGH_TEXTURES
  if (material.metalRoughTexture >= 0) {
    vec3 texel = sampleTexture(material.metalRoughTexture, uv);
    m = clamp(m * texel.b, 0.0, 1.0);
    float r = clamp(material.roughness * texel.g, 0.0, 1.0);
    material.kd = metalRoughKd(m, material.transmission);
    material.specularExponent = metalRoughExponent(r);
    material.ks = metalRoughKs(m, material.specularExponent);
    material.reflectivity = metalRoughReflectivity(m, r);
  }
#endif
  if (material.tintedMirror != 0u) material.specularColor = mix(vec3(1.0), baseColor, m);
}
#endif

// Whether the material draws a texture at all (the coursework shading model
// normalises plain colours but not texture colours).
bool isTextured(GpuMaterial material) {
#ifdef RT_FEATURE_TEXTURES
  return material.diffuseTexture >= 0;
#else
  return false;
#endif
}

// A texture's colour times the material's tint (the host sets the tint to
// white where the texture replaces the colour, as in the coursework files).
vec3 diffuseColorAt(GpuMaterial material, vec2 uv) {
#ifdef RT_FEATURE_TEXTURES
  if (material.diffuseTexture >= 0) {
    return material.diffuseColor * sampleTexture(material.diffuseTexture, uv);
  }
#endif
  return material.diffuseColor;
}

#endif
