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

// The wrap modes (RT_WRAP_*) of u and v: glTF samplers', where a scene has
// one that does not repeat; else repeat, folded away by the compiler.
uvec2 wrapModes(GpuTextureInfo info) {
#ifdef RT_FEATURE_TEXTURE_SAMPLERS
  return uvec2(info.flags >> RT_TEXTURE_WRAP_U_SHIFT, info.flags >> RT_TEXTURE_WRAP_V_SHIFT) &
         3u;
#else
  return uvec2(RT_WRAP_REPEAT);
#endif
}

// Texture coordinates in [0, 1] by the wrap modes: the fractional part
// (repeat; it also keeps coordinates small before scaling, so float
// precision holds far from 0), clamped, or mirrored every other period.
vec2 wrapCoordinates(vec2 uv, uvec2 modes) {
  vec2 wrapped = uv - floor(uv);
#ifdef RT_FEATURE_TEXTURE_SAMPLERS
  vec2 period2 = uv - 2.0 * floor(0.5 * uv);  // [0, 2)
  vec2 mirrored = mix(period2, 2.0 - period2, greaterThan(period2, vec2(1.0)));
  wrapped = mix(wrapped, clamp(uv, 0.0, 1.0), equal(modes, uvec2(RT_WRAP_CLAMP)));
  wrapped = mix(wrapped, mirrored, equal(modes, uvec2(RT_WRAP_MIRROR)));
#endif
  return wrapped;
}

// A texel coordinate in [-1, size] (the filter's neighbours of a wrapped
// coordinate) inside the texture: repeat wraps it without integer division
// (CPU drivers divide vectors one lane at a time); clamp and mirror, whose
// coordinates were folded into [0, 1], take the edge texel. Anything else
// (NaN texture coordinates) stays inside the texture.
uint wrapTexel(int x, int size, uint mode) {
  if (mode == RT_WRAP_REPEAT) {
    x = x < 0 ? x + size : x;
    x = x >= size ? x - size : x;
  }
  return uint(clamp(x, 0, size - 1));
}

uint texelWord(GpuTextureInfo info, int x, int y) {
  uvec2 modes = wrapModes(info);
  uint tx = wrapTexel(x, int(info.width), modes.x);
  uint ty = wrapTexel(y, int(info.height), modes.y);
  return textureTexel(info.firstTexel + ty * info.width + tx);
}

// A texel's colour, decoded from sRGB unless the texture holds data, and its
// alpha: coverage, stored linearly in sRGB images too.
vec4 fetchTexel(GpuTextureInfo info, int x, int y) {
  vec4 texel = unpackUnorm4x8(texelWord(info, x, y));
#if defined(RT_FEATURE_NORMAL_MAPS) || defined(RT_FEATURE_METAL_ROUGH_TEXTURES)
  if ((info.flags & RT_TEXTURE_LINEAR) != 0u) return texel;  // data, not colours
#endif
  return vec4(srgbToLinear(texel.rgb), texel.a);
}

// Bilinear filtering at `uv`: the texel (x, y) at the top left of the four
// around it, and the weights f of its right and lower neighbours. A
// nearest-texel sampler gets its texel at (x, y) with weights 0.
struct BilinearTaps {
  int x;
  int y;
  vec2 f;
};

BilinearTaps bilinearTaps(GpuTextureInfo info, vec2 uv) {
  vec2 size = vec2(info.width, info.height);
  vec2 wrapped = wrapCoordinates(uv, wrapModes(info));
#ifdef RT_FEATURE_TEXTURE_SAMPLERS
  if ((info.flags & RT_TEXTURE_NEAREST) != 0u) {
    vec2 texel = floor(wrapped * size);  // size itself at 1: clamped by wrapTexel
    return BilinearTaps(int(texel.x), int(texel.y), vec2(0.0));
  }
#endif
  vec2 pixel = wrapped * size - 0.5;
  vec2 base = floor(pixel);
  return BilinearTaps(int(base.x), int(base.y), pixel - base);
}

// Texture `index` at `uv`, filtered (colour and alpha alike; the callers'
// unused channels are compiled away).
vec4 sampleTextureRgba(int index, vec2 uv) {
  GpuTextureInfo info = loadTextureInfo(index);
  BilinearTaps at = bilinearTaps(info, uv);
  vec4 top = mix(fetchTexel(info, at.x, at.y), fetchTexel(info, at.x + 1, at.y), at.f.x);
  vec4 bottom =
      mix(fetchTexel(info, at.x, at.y + 1), fetchTexel(info, at.x + 1, at.y + 1), at.f.x);
  return mix(top, bottom, at.f.y);
}

vec3 sampleTexture(int index, vec2 uv) { return sampleTextureRgba(index, uv).rgb; }

float sampleTextureAlpha(int index, vec2 uv) { return sampleTextureRgba(index, uv).a; }
#endif

#ifdef RT_FEATURE_TRANSMISSION_TEXTURES
// A glTF material's transmission at a surface point: its factor times the
// red channel of its transmission texture, and the diffuse weight that
// leaves (metal_rough.h; a metallic-roughness texture's texel then refines
// it in applyMetalRough).
void applyTransmissionTexture(inout GpuMaterial material, vec2 uv) {
  if (material.transmissionTexture < 0) return;
  float t = sampleTexture(material.transmissionTexture, uv).r;
  material.transmission = clamp(material.transmission * t, 0.0, 1.0);
  material.kd = metalRoughKd(material.metallic, material.transmission);
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
  if ((material.flags & RT_MATERIAL_TINTED_MIRROR) != 0u) {
    material.specularColor = mix(vec3(1.0), baseColor, m);
  }
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
