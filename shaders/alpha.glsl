// Alpha cutouts (RT_FEATURE_ALPHA_CUTOUTS): whether a mesh triangle that a
// ray meets is there at that point, for materials whose alpha cuts holes
// (glTF alphaMode MASK and BLEND; GpuMaterial::alphaMode). Both walks, the
// renderer's BVH and the hardware's ray queries, ask it about each hit on an
// instance flagged RT_PRIM_ALPHA_CUTOUT, shadow rays included; through a
// hole the ray goes on as if the triangle were not there.
#ifndef RT_ALPHA_GLSL
#define RT_ALPHA_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "intersect.glsl"
#include "math.glsl"
#include "rng.glsl"
#include "textures.glsl"
#include "vertices.glsl"

// Texture coordinates of mesh triangle `item` at `barycentric`; (0, 0) for a
// mesh without vertex records (glTF: a texture without coordinates).
vec2 meshTriangleUv(uint item, vec2 barycentric, uint flags) {
#ifdef RT_FEATURE_VERTICES
  if ((flags & RT_PRIM_HAS_VERTICES) != 0u) {
    uvec3 corners = triangleVertices(itemRow(item, 0u), itemRow(item, 1u), itemRow(item, 2u));
    vec3 weights = cornerWeights(barycentric);
    return weights.x * vertexUv(corners.x) + weights.y * vertexUv(corners.y) +
           weights.z * vertexUv(corners.z);
  }
#endif
  return vec2(0.0);
}

// A number in [0, 1) that depends only on the ray (in world space, so that
// both walks agree) and the triangle: BLEND's coin. Two layers of one mesh
// get different coins for the same ray.
float blendCoin(Ray worldRay, uint item) {
  uvec3 o = floatBitsToUint(worldRay.origin);
  uvec3 d = floatBitsToUint(worldRay.direction);
  return unitFloat(hashCounter(uvec4(o.x ^ d.z, o.y ^ (d.x * 0x9e3779b9u),
                                     o.z ^ (d.y * 0x85ebca6bu), item))
                       .x);
}

// Whether mesh triangle `item` of top-level primitive `instance` is there at
// `barycentric` for `worldRay`.
bool alphaCovers(uint instance, uint item, vec2 barycentric, Ray worldRay) {
  uvec4 info = primitiveInfo(instance);  // kind, material, shape, flags
  if ((info.w & RT_PRIM_ALPHA_CUTOUT) == 0u) return true;
  MaterialAlpha material = loadMaterialAlpha(info.y);
  float alpha = material.factor;
#ifdef RT_FEATURE_TEXTURES
  if (material.texture >= 0) {
    alpha *= sampleTextureAlpha(material.texture, meshTriangleUv(item, barycentric, info.w));
  }
#endif
  if (material.mode == RT_ALPHA_MASK) return alpha >= material.cutoff;
  if (material.mode == RT_ALPHA_BLEND) return blendCoin(worldRay, item) < alpha;
  return true;
}

#endif
