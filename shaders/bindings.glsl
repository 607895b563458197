// Scene buffers shared by every kernel that traces rays (set 0).
#ifndef RT_BINDINGS_GLSL
#define RT_BINDINGS_GLSL

#include "gpu_types.h"

// A uniform block: GpuSceneInfo has only vec3 + scalar pairs and scalars, so
// its std140 layout is its std430 one. (CPU drivers read storage buffers
// lane by lane inside loops and branches, even at a shared index.)
layout(std140, set = 0, binding = RT_BINDING_SCENE_INFO) uniform SceneInfoBlock {
  GpuSceneInfo sceneInfoBlock;
};

// Uniform and push-constant values never decide a branch or a loop count
// directly. Lavapipe (Mesa 22.x) "inlines" such values: it bakes them into
// a recompiled kernel each time they may have changed, which is at every
// dispatch (push constants are set and descriptor sets bound each time):
// 20-30 ms of driver work per dispatch while the worker threads wait, and on
// a scene's first render a full compile per dispatch. Passed through
// opaqueZero(), which is 0 in every invocation but nothing a compiler can
// fold, they are out of its reach, and the kernel compiles once, when its
// pipeline is created. The bits are unchanged, so results are too.
uint opaqueZero() { return min(gl_NumWorkGroups.z, 1u) - 1u; }  // a dispatch has >= 1 group

uint opaqueUint(uint value, uint zero) { return value + zero; }
uvec2 opaqueUint(uvec2 value, uint zero) { return value + zero; }
float opaqueFloat(float value, uint zero) { return uintBitsToFloat(floatBitsToUint(value) + zero); }
vec3 opaqueFloat(vec3 value, uint zero) { return uintBitsToFloat(floatBitsToUint(value) + zero); }

// The scene constants every function reads: sceneInfoBlock through
// opaqueZero(). Every kernel's main() calls loadSceneInfo() first.
GpuSceneInfo sceneInfo;

void loadSceneInfo() {
  uint z = opaqueZero();
  GpuSceneInfo b = sceneInfoBlock;
  sceneInfo = GpuSceneInfo(
      opaqueFloat(b.cameraPosition, z), opaqueFloat(b.tanHalfFovY, z),
      opaqueFloat(b.cameraRight, z), opaqueFloat(b.aspect, z), opaqueFloat(b.cameraUp, z),
      opaqueFloat(b.apertureRadius, z), opaqueFloat(b.cameraForward, z),
      opaqueFloat(b.focusDistance, z), opaqueFloat(b.backgroundColor, z),
      opaqueUint(b.maxBounces, z), opaqueFloat(b.binaryHitColor, z), opaqueUint(b.renderMode, z),
      opaqueUint(b.width, z), opaqueUint(b.height, z), opaqueUint(b.pointLightCount, z),
      opaqueUint(b.primitiveCount, z), opaqueUint(b.bvhNodeCount, z),
      opaqueUint(b.lightFalloff, z), opaqueFloat(b.lightScale, z), opaqueUint(b.shadingModel, z),
      opaqueUint(b.sphereUvPole, z), opaqueUint(b.textureCount, z),
      opaqueUint(b.areaLightCount, z), opaqueUint(b.distributedBounces, z),
      opaqueFloat(b.ambient, z), opaqueFloat(b.indirectClamp, z),
      opaqueUint(b.mirrorsReplaceLocalLight, z), opaqueUint(b.areaLightSamples, z),
      opaqueUint(b.soleInstance, z), opaqueFloat(b.branchBailout, z));
}

// The scene arrays (records of whole 16-byte rows, gpu_types.h) are texel
// buffers, or with RT_SCENE_STORAGE_BUFFERS storage buffers of the same
// bytes (--scene-arrays; encode/SceneBuffers.hpp says what each measured).
// CPU drivers such as lavapipe gather texels with vector loads but read
// storage buffers at divergent indices one lane at a time.
// RT_FLOAT_ROWS / RT_UINT_ROWS declare an array of vec4 / uvec4 rows,
// RT_UINT_WORDS one of single uints; RT_ROW and RT_WORD read one.
#ifdef RT_SCENE_STORAGE_BUFFERS
#define RT_FLOAT_ROWS(bindingIndex, name) \
  layout(std430, set = 0, binding = bindingIndex) restrict readonly buffer name##Block { vec4 name[]; };
#define RT_UINT_ROWS(bindingIndex, name) \
  layout(std430, set = 0, binding = bindingIndex) restrict readonly buffer name##Block { uvec4 name[]; };
#define RT_UINT_WORDS(bindingIndex, name) \
  layout(std430, set = 0, binding = bindingIndex) restrict readonly buffer name##Block { uint name[]; };
#define RT_ROW(name, index) name[index]
#define RT_WORD(name, index) name[index]
#else
#define RT_FLOAT_ROWS(bindingIndex, name) \
  layout(set = 0, binding = bindingIndex) uniform textureBuffer name;
#define RT_UINT_ROWS(bindingIndex, name) \
  layout(set = 0, binding = bindingIndex) uniform utextureBuffer name;
#define RT_UINT_WORDS(bindingIndex, name) RT_UINT_ROWS(bindingIndex, name)
#define RT_ROW(name, index) texelFetch(name, int(index))
#define RT_WORD(name, index) texelFetch(name, int(index)).x
#endif

RT_FLOAT_ROWS(RT_BINDING_PRIMITIVES, primitiveTexels)
RT_UINT_ROWS(RT_BINDING_BVH_NODES, bvhNodeTexels)

// Shading data of top-level primitive `index` (GpuPrimitive), texel `row`
// (0..3): a, b, c, then kind/material/shape/flags.
vec4 primitiveRow(uint index, uint row) {
  return RT_ROW(primitiveTexels, index * RT_TEXELS_PER_PRIMITIVE + row);
}

uvec4 primitiveInfo(uint index) { return floatBitsToUint(primitiveRow(index, 3u)); }

GpuPrimitive loadPrimitive(uint index) {
  uvec4 info = primitiveInfo(index);
  return GpuPrimitive(primitiveRow(index, 0u), primitiveRow(index, 1u), primitiveRow(index, 2u),
                      info.x, info.y, info.z, info.w);
}

// Texel `row` (0..1) of BVH node `index` (see GpuBvhNode).
uvec4 nodeRow(uint index, uint row) {
  return RT_ROW(bvhNodeTexels, index * RT_TEXELS_PER_BVH_NODE + row);
}

RT_FLOAT_ROWS(RT_BINDING_ITEMS, itemTexels)

// Texel `row` (0..2) of leaf item `index` (see GpuItem).
vec4 itemRow(uint index, uint row) {
  return RT_ROW(itemTexels, index * RT_TEXELS_PER_ITEM + row);
}

// Materials and point lights (read at every hit and for every light).
RT_UINT_ROWS(RT_BINDING_MATERIALS, materialTexels)
RT_FLOAT_ROWS(RT_BINDING_POINT_LIGHTS, pointLightTexels)

// Texel `row` (0..6) of material `index` (see GpuMaterial).
uvec4 materialRow(uint index, uint row) {
  return RT_ROW(materialTexels, index * RT_TEXELS_PER_MATERIAL + row);
}

// GpuMaterial's alpha fields, its row RT_MATERIAL_ALPHA_ROW: the walk reads
// them on their own (alpha.glsl).
struct MaterialAlpha {
  int texture;
  uint mode;
  float factor;
  float cutoff;
};

MaterialAlpha loadMaterialAlpha(uint index) {
  uvec4 row = materialRow(index, RT_MATERIAL_ALPHA_ROW);
  return MaterialAlpha(int(row.x), row.y, uintBitsToFloat(row.z), uintBitsToFloat(row.w));
}

GpuMaterial loadMaterial(uint index) {
  vec4 diffuse = uintBitsToFloat(materialRow(index, 0u));
  vec4 specular = uintBitsToFloat(materialRow(index, 1u));
  vec4 emission = uintBitsToFloat(materialRow(index, 2u));
  uvec4 optics = materialRow(index, 3u);
  uvec4 profile = materialRow(index, 4u);
#if defined(RT_FEATURE_METAL_ROUGH_TEXTURES) || defined(RT_FEATURE_TINTED_MIRRORS) || \
    defined(RT_FEATURE_TINTED_TRANSMISSION) || defined(RT_FEATURE_THIN_WALLS)
  uvec4 metalRough = materialRow(index, 5u);
#else
  // Not read where no material needs it: one fetch less a hit.
  uvec4 metalRough = uvec4(uint(-1), floatBitsToUint(0.0), floatBitsToUint(1.0), 0u);
#endif
#ifdef RT_FEATURE_ALPHA_CUTOUTS
  MaterialAlpha alpha = loadMaterialAlpha(index);
#else
  MaterialAlpha alpha = MaterialAlpha(-1, RT_ALPHA_OPAQUE, 1.0, 0.0);
#endif
#ifdef RT_FEATURE_TRANSMISSION_TEXTURES
  uvec4 transmissionRow = materialRow(index, 7u);
#else
  uvec4 transmissionRow = uvec4(uint(-1), 0u, 0u, 0u);
#endif
  return GpuMaterial(diffuse.xyz, diffuse.w, specular.xyz, specular.w, emission.xyz, emission.w,
                     uintBitsToFloat(optics.x), uintBitsToFloat(optics.y),
                     uintBitsToFloat(optics.z), int(optics.w), profile.x, int(profile.y),
                     uintBitsToFloat(profile.z), int(profile.w), int(metalRough.x),
                     uintBitsToFloat(metalRough.y), uintBitsToFloat(metalRough.z), metalRough.w,
                     alpha.texture, alpha.mode, alpha.factor, alpha.cutoff,
                     int(transmissionRow.x), transmissionRow.y, transmissionRow.z,
                     transmissionRow.w);
}

// Texel `row` (0..2) of point light `index` (see GpuPointLight).
vec4 pointLightRow(uint index, uint row) {
  return RT_ROW(pointLightTexels, index * RT_TEXELS_PER_POINT_LIGHT + row);
}

GpuPointLight loadPointLight(uint index) {
  vec4 position = pointLightRow(index, 0u);
  vec4 diffuse = pointLightRow(index, 1u);
  vec4 specular = pointLightRow(index, 2u);
  return GpuPointLight(position.xyz, position.w, diffuse.xyz, diffuse.w, specular.xyz, specular.w);
}

#endif
