// The one definition of every structure the host shares with the shaders.
// Included by C++ (src/render, src/gpu, tests) and by GLSL (shaders/*.comp).
// Layout rule: std430 everywhere (storage buffers and push constants); every
// vec3 starts on a 16-byte boundary and is followed by a 4-byte scalar, so the
// C++ (glm, 4-byte aligned) and GLSL layouts coincide. The size asserts below
// catch any drift at compile time.
#ifndef RT_GPU_TYPES_H
#define RT_GPU_TYPES_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace rt::gpu {
using glm::uvec2;
using glm::uvec4;
using glm::vec3;
using glm::vec4;
using uint = uint32_t;
#define RT_ASSERT_STD430_SIZE(T, bytes)                                                           \
  static_assert(sizeof(T) == (bytes), #T ": size differs from std430");                           \
  static_assert(sizeof(T) % 16 == 0 || sizeof(T) < 16, #T ": array stride must be a multiple of " \
                                                          "16")
#else
#define RT_ASSERT_STD430_SIZE(T, bytes)
#endif

// Descriptor set 0 bindings of the render and intersection kernels.
#define RT_BINDING_SCENE_INFO 0
#define RT_BINDING_PRIMITIVES 1
#define RT_BINDING_BVH_NODES 2
#define RT_BINDING_MATERIALS 3
#define RT_BINDING_POINT_LIGHTS 4
#define RT_BINDING_ACCUMULATION 5
#define RT_BINDING_RAYS 6
#define RT_BINDING_HITS 7
#define RT_BINDING_RAY_COUNTER 8  // only when compiled with RT_COUNT_RAYS
#define RT_BINDING_VERTICES 9
#define RT_BINDING_TEXTURE_INFO 10
#define RT_BINDING_TEXELS 11

#define RT_WORKGROUP_SIZE_X 8
#define RT_WORKGROUP_SIZE_Y 8
#define RT_BATCH_WORKGROUP_SIZE 64

// The BVH builder never exceeds this depth, so traversal needs no more stack.
#define RT_BVH_MAX_DEPTH 48

// GpuPrimitive::kind
#define RT_PRIM_SPHERE 0u
#define RT_PRIM_TRIANGLE 1u
#define RT_PRIM_CYLINDER 2u

// GpuPrimitive::flags
#define RT_PRIM_HAS_VERTICES 1u  // triangle: a.w, b.w, c.w hold GpuVertex indices (bits)
#define RT_PRIM_SMOOTH 2u        // triangle: interpolate the vertices' normals

// GpuSceneInfo::renderMode
#define RT_MODE_BINARY 0u
#define RT_MODE_PHONG 1u

// GpuSceneInfo::shadingModel
#define RT_SHADING_STANDARD 0u    // per-channel Blinn-Phong: kd*Cd*Id*cos + ks*Cs*Is*spec
#define RT_SHADING_COURSEWORK 1u  // the official Path-of-Light renders: see README "Conventions"

// GpuSceneInfo::lightFalloff: how point-light intensity decays with distance d
#define RT_FALLOFF_NONE 0u
#define RT_FALLOFF_INVERSE_SQUARE 1u

// GpuFrameParams::samplerKind
#define RT_SAMPLER_RANDOM 0u
#define RT_SAMPLER_JITTERED 1u

// One surface primitive (64 bytes). Quads are split into two triangles on the
// host; mesh triangles use the same record.
//   sphere:   a = (center, radius)
//   triangle: a = (v0, i0), b = (v1, i1), c = (v2, i2) where the i are
//             GpuVertex indices (as float bits) if RT_PRIM_HAS_VERTICES;
//             vertices, not edges, so that triangles sharing a vertex see
//             the same floats (watertight intersection)
//   cylinder: a = (center, radius), b = (unit axis, half height)
struct GpuPrimitive {
  vec4 a;
  vec4 b;
  vec4 c;
  uint kind;
  uint materialIndex;
  uint shapeIndex;  // index of the scene shape it came from
  uint flags;
};
RT_ASSERT_STD430_SIZE(GpuPrimitive, 64);
#define RT_TEXELS_PER_PRIMITIVE 4u  // read as RGBA32F texels (bindings.glsl)

// Binary BVH node (32 bytes). count == 0: interior node whose children are
// firstIndex and firstIndex + 1; count > 0: leaf over primitives
// [firstIndex, firstIndex + count) of the (reordered) primitive buffer.
struct GpuBvhNode {
  vec3 boundsMin;
  uint firstIndex;
  vec3 boundsMax;
  uint count;
};
RT_ASSERT_STD430_SIZE(GpuBvhNode, 32);
#define RT_TEXELS_PER_BVH_NODE 2u

struct GpuMaterial {
  vec3 diffuseColor;
  float kd;
  vec3 specularColor;
  float ks;
  float specularExponent;
  float reflectivity;
  float transmission;
  float ior;
  int diffuseTexture;  // index into the texture table, -1: none
  uint pad0;
  uint pad1;
  uint pad2;
};
RT_ASSERT_STD430_SIZE(GpuMaterial, 64);

// Per-vertex shading data of triangles (meshes, and quads/triangles for UVs).
struct GpuVertex {
  vec3 normal;  // unit, object normal transformed to world space
  float u;
  float v;
  float pad0;
  float pad1;
  float pad2;
};
RT_ASSERT_STD430_SIZE(GpuVertex, 32);

// Where one texture's texels start in the texel buffer (RGBA8, sRGB, one uint
// per texel, rows top to bottom).
struct GpuTextureInfo {
  uint firstTexel;
  uint width;
  uint height;
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuTextureInfo, 16);

struct GpuPointLight {
  vec3 position;
  float pad0;
  vec3 diffuseIntensity;
  float pad1;
  vec3 specularIntensity;
  float pad2;
};
RT_ASSERT_STD430_SIZE(GpuPointLight, 48);

// Per-scene constants (one record in a storage buffer).
struct GpuSceneInfo {
  vec3 cameraPosition;
  float tanHalfFovY;
  vec3 cameraRight;  // unit, image +x
  float aspect;      // width / height
  vec3 cameraUp;     // unit, image +y (rows go down)
  float apertureRadius;
  vec3 cameraForward;
  float focusDistance;
  vec3 backgroundColor;
  uint maxBounces;
  vec3 binaryHitColor;
  uint renderMode;
  uint width;
  uint height;
  uint pointLightCount;
  uint primitiveCount;
  uint bvhNodeCount;
  uint lightFalloff;
  float lightScale;  // multiplies every light intensity
  uint shadingModel;
  uint sphereUvPole;  // 0, 1, 2: world axis through the poles of sphere UVs
  uint textureCount;
  uint pad0;
  uint pad1;
};
RT_ASSERT_STD430_SIZE(GpuSceneInfo, 144);

// Push constants of one dispatch of the render kernel.
struct GpuFrameParams {
  uvec2 tileOrigin;   // first pixel of the dispatched tile
  uvec2 tileSize;     // pixels covered by the dispatch
  uint sampleBegin;   // first sample index this dispatch adds
  uint sampleCount;   // samples per pixel this dispatch adds
  uint samplesTotal;  // total samples the render aims for (stratification)
  uint seed;
  uint samplerKind;
  uint pad0;
  uint pad1;
  uint pad2;
};
RT_ASSERT_STD430_SIZE(GpuFrameParams, 48);

// Intersection test kernel I/O (tests/gpu): one ray in, one hit out.
struct GpuRay {
  vec3 origin;
  float tMin;
  vec3 direction;
  float tMax;
};
RT_ASSERT_STD430_SIZE(GpuRay, 32);

struct GpuHit {
  vec3 normal;  // geometric, unit, facing the side the ray came from
  float t;      // < 0: no hit
  uint primitiveIndex;
  uint shapeIndex;
  uint occluded;  // any-hit (shadow) query result for the same ray
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuHit, 32);

struct GpuBatchParams {
  uint rayCount;
  uint pad0;
  uint pad1;
  uint pad2;
};
RT_ASSERT_STD430_SIZE(GpuBatchParams, 16);

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_GPU_TYPES_H
