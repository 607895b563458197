// The one definition of every structure the host shares with the shaders.
// Included by C++ (src/encode, src/render, src/gpu, tests) and by GLSL.
// Layout rule: every vec3 starts on a 16-byte boundary and is followed by a
// 4-byte scalar, so the C++ (glm, 4-byte aligned), std430 and std140 layouts
// coincide. Scene arrays are read as RGBA32 texels (records of whole texels,
// by the readers in bindings.glsl, lights.glsl, surface.glsl, textures.glsl),
// GpuSceneInfo as a std140 uniform block, GpuFrameParams as push constants.
// The asserts below check sizes at compile time; tests/gpu/test_gpu_layout
// checks every field's offset through the shaders' own readers.
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
#define RT_ASSERT_STD430_SIZE(T, bytes)                                 \
  static_assert(sizeof(T) == (bytes), #T ": size differs from std430"); \
  static_assert(sizeof(T) % 16 == 0 || sizeof(T) < 16, #T               \
                ": array stride must be a multiple of "                 \
                "16")
// A function both sides compile from this file.
#define RT_SHARED_FUNCTION inline
// A record read from a texel buffer as `texels` RGBA32 texels.
#define RT_ASSERT_TEXELS(T, texels) \
  static_assert(sizeof(T) == (texels)*16, #T ": not a whole number of RGBA32 texels")
#else
#define RT_ASSERT_STD430_SIZE(T, bytes)
#define RT_ASSERT_TEXELS(T, texels)
#define RT_SHARED_FUNCTION
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
// Sums of the odd-indexed samples alone (the error estimate's second half).
#define RT_BINDING_ACCUMULATION_ODD 13
#define RT_BINDING_ITEMS 12
#define RT_BINDING_AREA_LIGHTS 14
#define RT_BINDING_EMITTERS 15
// The top-level acceleration structure (--accel hardware only).
#define RT_BINDING_TLAS 16
// Adaptive sampling's per-tile sample ranges (RT_ADAPTIVE_SAMPLING only).
#define RT_BINDING_SAMPLE_PLAN 17
// Adaptive sampling's per-tile count of the rays traced since the host last
// read it: the cost of a tile's samples (RT_ADAPTIVE_SAMPLING only).
#define RT_BINDING_TILE_RAYS 18
// Adaptive sampling's per-pixel edge samples: what the edge round adds to
// each pixel beyond its tile's count (RT_ADAPTIVE_SAMPLING only).
#define RT_BINDING_PIXEL_EXTRAS 19
// The render kernel's work queue on CPU devices: the next run of pixels a
// subgroup takes (RT_WORK_QUEUE only; trace.comp).
#define RT_BINDING_WORK_QUEUE 20

#define RT_WORKGROUP_SIZE_X 8
#define RT_WORKGROUP_SIZE_Y 8
#define RT_BATCH_WORKGROUP_SIZE 64
// Adaptive sampling decides per square tile of this many pixels a side
// (one workgroup, so that a workgroup's lanes run the same sample count).
#define RT_ADAPTIVE_TILE_SIZE 8
// Flags in a tile's (first sample, count) of the sample plan, for the pixels
// adaptivePairedPixel picks: in the first round's count, "one sample more"
// (they hold the tile's noise estimate); in later rounds' first sample, "one
// later" (they already have that extra sample).
#define RT_ADAPTIVE_PAIRED_FLAG 0x80000000u
// A second flag for the edge round (AdaptiveSampling.hpp): in its count,
// "plus the pixel's extras" (RT_BINDING_PIXEL_EXTRAS); in later rounds' first
// sample, "later by the pixel's extras".
#define RT_ADAPTIVE_EXTRAS_FLAG 0x40000000u
#define RT_ADAPTIVE_PLAN_FLAGS (RT_ADAPTIVE_PAIRED_FLAG | RT_ADAPTIVE_EXTRAS_FLAG)
// adaptivePairedPixel picks blocks of a tile this size.
#define RT_ADAPTIVE_PAIR_BLOCK_WIDTH 4
#define RT_ADAPTIVE_PAIR_BLOCK_HEIGHT 2

// The BVH builder never exceeds this depth, so traversal needs no more stack.
#define RT_BVH_MAX_DEPTH 48

// GpuPrimitive::kind
#define RT_PRIM_SPHERE 0u
#define RT_PRIM_TRIANGLE 1u
#define RT_PRIM_CYLINDER 2u

// GpuPrimitive::flags
#define RT_PRIM_HAS_VERTICES 1u  // triangle: a.w, b.w, c.w hold GpuVertex indices (bits)
#define RT_PRIM_SMOOTH 2u        // triangle: interpolate the vertices' normals
// Mesh instance: its material's alpha cuts holes (GpuMaterial::alphaMode),
// so the walk asks the material about each hit (shaders/alpha.glsl).
#define RT_PRIM_ALPHA_CUTOUT 4u

// GpuSceneInfo::renderMode
#define RT_MODE_BINARY 0u
#define RT_MODE_PHONG 1u
#define RT_MODE_PATH_TRACER 2u

// GpuSceneInfo::shadingModel
#define RT_SHADING_STANDARD 0u    // per-channel Blinn-Phong: kd*Cd*Id*cos + ks*Cs*Is*spec
#define RT_SHADING_COURSEWORK 1u  // the official Path-of-Light renders: see README "Conventions"

// GpuSceneInfo::lightFalloff: how point-light intensity decays with distance d
#define RT_FALLOFF_NONE 0u
#define RT_FALLOFF_INVERSE_SQUARE 1u

// GpuFrameParams::samplerKind
#define RT_SAMPLER_RANDOM 0u
#define RT_SAMPLER_JITTERED 1u
#define RT_SAMPLER_SOBOL 2u  // Owen-scrambled Sobol (rng.glsl)
// Flag on samplerKind: even and odd pixel samples are two independent
// replicates (for the error estimate; see rng.glsl).
#define RT_SAMPLER_REPLICATES 0x100u

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
RT_ASSERT_TEXELS(GpuPrimitive, RT_TEXELS_PER_PRIMITIVE);

// ---- Acceleration structure (src/render/FlatScene, shaders/traverse.glsl) ----
// Two levels: a top-level BVH whose leaves are single items (a shape's
// sphere, cylinder or triangle, or a mesh instance), and one BVH per mesh
// over its triangles, shared by all its instances (in world space when the
// mesh is placed once, else in object space). All nodes
// share one array (the top-level root is node 0); all leaf items share one
// GpuItem array (top-level items first, numbered like GpuPrimitive).
//
// Node (32 bytes, two RGBA32UI texels) holding the boxes of both children,
// so one fetch decides which children a ray enters. Boxes are half floats
// (packHalf2x16 pairs), rounded outwards: looser by at most one half ulp,
// never missing anything. A child reference is a node index or, with
// RT_REF_LEAF set, a leaf:
//   top level:  RT_REF_LEAF | (kind + 1) << RT_REF_COUNT_SHIFT | item   (RT_PRIM_*)
//   mesh level: RT_REF_LEAF | RT_REF_MESH | count << RT_REF_COUNT_SHIFT | first triangle item
// (RT_REF_LEAF alone is the empty leaf; a leaf tells its level, so the walk
// keeps no level of its own). Node 1 + i is a copy of the mesh root of
// top-level item i, for each mesh instance i (instances are the first items).
struct GpuBvhNode {
  uint leftRef;
  uint rightRef;
  uint leftMinXY;
  uint leftMinZMaxX;
  uint leftMaxYZ;
  uint rightMinXY;
  uint rightMinZMaxX;
  uint rightMaxYZ;
};
RT_ASSERT_STD430_SIZE(GpuBvhNode, 32);
#define RT_TEXELS_PER_BVH_NODE 2u
RT_ASSERT_TEXELS(GpuBvhNode, RT_TEXELS_PER_BVH_NODE);
#define RT_REF_LEAF 0x80000000u
#define RT_REF_COUNT_SHIFT 27u
#define RT_REF_MAX_LEAF_SIZE 15u
#define RT_REF_MESH 0x04000000u
#define RT_REF_FIRST_MASK 0x03ffffffu

// What a leaf points at (48 bytes, three texels), by kind:
//   triangle: v0, v1, v2 (the corners: the watertight test needs them exactly);
//             w: GpuVertex indices of the corners (bits)
//   sphere:   (center, radius), unused, unused
//   cylinder: (center, radius), (unit axis, half height), unused
//   instance: rows of the world-to-object matrix (3x4)
// Mesh triangles are in their BVH's space (world or object, see above).
struct GpuItem {
  vec4 row0;
  vec4 row1;
  vec4 row2;
};
RT_ASSERT_STD430_SIZE(GpuItem, 48);
#define RT_TEXELS_PER_ITEM 3u
RT_ASSERT_TEXELS(GpuItem, RT_TEXELS_PER_ITEM);

// GpuPrimitive of kind RT_PRIM_INSTANCE (shading data of a mesh instance):
// a, b, c are the rows of the world-to-object matrix; flags holds
// RT_PRIM_HAS_VERTICES / RT_PRIM_SMOOTH of its mesh.
#define RT_PRIM_INSTANCE 3u

// Traversal stack: the farther children waiting at both levels, plus the
// marker that ends a mesh instance (traverse.glsl).
#define RT_BVH_STACK_SIZE (2 * RT_BVH_MAX_DEPTH + 8)
// Of which the top entries are held in registers; a walk pushes at most one
// entry per level of its path (and the marker), so a scene whose levels and
// marker come to at most this many never needs the rest
// (ShaderFeatures::stackInRegisters).
#define RT_BVH_STACK_REGISTERS 4
// ---- end of acceleration structure ----

struct GpuMaterial {
  vec3 diffuseColor;
  float kd;
  vec3 specularColor;
  float ks;
  // Area lights: radiance leaving the surface, times pi (README "Area lights");
  // a glow (RT_EMISSION_GLOW, _UNLIT): the radiance it shows, times its texture.
  vec3 emission;
  float specularExponent;
  float reflectivity;
  float transmission;
  float ior;
  int diffuseTexture;    // index into the texture table, -1: none
  uint emissionProfile;  // RT_EMISSION_*: how emission depends on the view
  int normalTexture;     // tangent-space normal map (glTF normalTexture), -1: none
  float normalScale;     // its x and y scale (glTF normalTexture.scale)
  int emissionTexture;   // a glow's texture (glTF emissiveTexture, unlit base colour), -1: none
  // A glTF metallic-roughness texture (data: blue metallic, green roughness),
  // -1: none; where there is one, each texel times these factors gives kd,
  // ks, the exponent and the reflectivity at a point (metal_rough.h; the
  // fields above hold those of the texture's mean). Without one, the
  // material's metallic and roughness. Read with tintedMirror.
  int metalRoughTexture;
  float metallic;
  float roughness;
  // RT_MATERIAL_* flags, none in the coursework files. TINTED_MIRROR: mirror
  // reflections are tinted by specularColor (glTF: a metal's Fresnel
  // reflectance at normal incidence is its base colour). TINTED_TRANSMISSION:
  // light through the surface takes the base colour at the point (glTF's
  // transmission). THIN_WALLED: light passes through the surface without
  // bending, a thin shell rather than the face of a solid (glTF's
  // transmission without KHR_materials_volume's thickness).
  uint flags;
  // Where the surface is there at all (glTF alphaMode; RT_ALPHA_*): alpha is
  // alphaFactor times the alpha channel of texture alphaTexture (-1: none)
  // at the point. Read by the walk (shaders/alpha.glsl), not by shading.
  int alphaTexture;
  uint alphaMode;
  float alphaFactor;
  float alphaCutoff;  // RT_ALPHA_MASK: there where alpha >= alphaCutoff
  // glTF's transmission texture (-1: none): transmission is the factor
  // above times its red channel at the point, and kd follows (metal_rough.h).
  int transmissionTexture;
  uint pad0;
  uint pad1;
  uint pad2;
};
RT_ASSERT_STD430_SIZE(GpuMaterial, 128);
#define RT_MATERIAL_TINTED_MIRROR 1u
#define RT_MATERIAL_TINTED_TRANSMISSION 2u
#define RT_MATERIAL_THIN_WALLED 4u
// Read as RGBA32UI texels (bindings.glsl loadMaterial): rows diffuse/kd,
// specular/ks, emission/exponent, reflectivity/transmission/ior/texture,
// profile/normal map/emission texture, metallic-roughness texture/factors/
// flags (read only where a feature needs them), alpha (read by the walk
// only, where RT_FEATURE_ALPHA_CUTOUTS is built), transmission texture (read
// only where RT_FEATURE_TRANSMISSION_TEXTURES is built).
#define RT_TEXELS_PER_MATERIAL 8u
#define RT_MATERIAL_ALPHA_ROW 6u
RT_ASSERT_TEXELS(GpuMaterial, RT_TEXELS_PER_MATERIAL);

// GpuMaterial::alphaMode (glTF alphaMode)
#define RT_ALPHA_OPAQUE 0u  // there everywhere
#define RT_ALPHA_MASK 1u    // there where alpha >= alphaCutoff, a hole elsewhere
// There for a share alpha of the rays, which pass through it elsewhere: a
// hash of the ray and the triangle decides (stochastic transparency, as in
// pbrt-v4), so samples average to alpha blending, and a ray always gets the
// same answer (renders stay a function of the samples).
#define RT_ALPHA_BLEND 2u

// How an area light's surface emits (GpuMaterial::emissionProfile,
// GpuAreaLight::profile). Spheres are always lamps (Lambertian).
#define RT_EMISSION_ISOTROPIC 0u   // each point shines equally in all directions (coursework)
#define RT_EMISSION_LAMBERTIAN 1u  // radiance the same in every direction (physical)
// Not a light: the surface shows emission times its emission texture to the
// rays that count emission (camera, mirror, refraction), and lights nothing
// (glTF emissive textures, whose detail cannot be one light).
#define RT_EMISSION_GLOW 2u
// A glow of the surface's base colour (glTF KHR_materials_unlit): as
// RT_EMISSION_GLOW, and times the vertex colours too, as base colours are
// (glTF multiplies a base colour by COLOR_0, never an emissive one).
#define RT_EMISSION_UNLIT 3u

// Whether a material of emission profile `profile` is a glow (shows its
// emission, lights nothing) rather than an area light or nothing.
RT_SHARED_FUNCTION bool isGlowProfile(uint profile) {
  return profile == RT_EMISSION_GLOW || profile == RT_EMISSION_UNLIT;
}

// ---- Area lights (src/render/AreaLights.cpp, shaders/lights.glsl) ----
// An area light is a list of emitter pieces (a sphere, a cylinder, or the
// triangles of a quad, triangle or mesh), its intensity shared evenly over
// their area. Isotropic lights (the coursework's): every point shines like a
// point light, equally in all directions. Lambertian lights: the same power,
// with the radiance the same in every direction (both faces of triangles).
// A piece is chosen by its share of the area, then a point on it. Spheres
// are lamps (Lambertian) sampled by the cone they subtend.
struct GpuAreaLight {
  vec3 diffuseIntensity;  // as GpuPointLight, the whole light's
  uint firstEmitter;
  vec3 specularIntensity;
  uint emitterCount;
  float area;    // total area of the pieces
  uint samples;  // shadow rays per shading point and pixel sample
  uint profile;  // RT_EMISSION_*
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuAreaLight, 48);
#define RT_TEXELS_PER_AREA_LIGHT 3u  // RGBA32UI texels (lights.glsl loadAreaLight)
RT_ASSERT_TEXELS(GpuAreaLight, RT_TEXELS_PER_AREA_LIGHT);

// GpuEmitter::kind (the RT_PRIM_* numbers)
//   sphere:   a = (center, radius)
//   triangle: a, b, c = corners
//   cylinder: a = (center, radius), b = (unit axis, half height)
struct GpuEmitter {
  vec4 a;
  vec4 b;
  vec4 c;
  uint kind;
  float cdfEnd;  // share of the light's area of the pieces up to this one
  float area;
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuEmitter, 64);
#define RT_TEXELS_PER_EMITTER 4u  // RGBA32UI texels (lights.glsl loadEmitter)
RT_ASSERT_TEXELS(GpuEmitter, RT_TEXELS_PER_EMITTER);
// ---- end of area lights ----

// Per-vertex shading data of triangles (meshes, and quads/triangles for UVs).
struct GpuVertex {
  vec3 normal;  // unit, object normal transformed to world space
  float u;
  vec3 color;  // linear RGB the diffuse colour is multiplied by (white: none)
  float v;
};
RT_ASSERT_STD430_SIZE(GpuVertex, 32);
#define RT_TEXELS_PER_VERTEX 2u  // RGBA32F texels (surface.glsl loadVertex)
RT_ASSERT_TEXELS(GpuVertex, RT_TEXELS_PER_VERTEX);

// Where one texture's texels start in the texel buffer (RGBA8, sRGB, one uint
// per texel, rows top to bottom; read as an R32UI texel buffer).
struct GpuTextureInfo {
  uint firstTexel;
  uint width;
  uint height;
  uint flags;  // RT_TEXTURE_*
};
// GpuTextureInfo::flags: data or colours, and the sampling (TextureSampling;
// read only where RT_FEATURE_TEXTURE_SAMPLERS is built).
#define RT_TEXTURE_LINEAR 1u        // the texels are data (a normal map), else sRGB-encoded colours
#define RT_TEXTURE_NEAREST 2u       // the nearest texel, else bilinear filtering
#define RT_TEXTURE_WRAP_U_SHIFT 2u  // RT_WRAP_* of u in bits 2-3
#define RT_TEXTURE_WRAP_V_SHIFT 4u  // and of v in bits 4-5
#define RT_WRAP_REPEAT 0u
#define RT_WRAP_CLAMP 1u
#define RT_WRAP_MIRROR 2u
RT_ASSERT_STD430_SIZE(GpuTextureInfo, 16);
#define RT_TEXELS_PER_TEXTURE_INFO 1u  // one RGBA32UI texel (textures.glsl)
RT_ASSERT_TEXELS(GpuTextureInfo, RT_TEXELS_PER_TEXTURE_INFO);

struct GpuPointLight {
  vec3 position;
  float pad0;
  vec3 diffuseIntensity;
  float pad1;
  vec3 specularIntensity;
  float pad2;
};
RT_ASSERT_STD430_SIZE(GpuPointLight, 48);
#define RT_TEXELS_PER_POINT_LIGHT 3u  // RGBA32F texels (bindings.glsl loadPointLight)
RT_ASSERT_TEXELS(GpuPointLight, RT_TEXELS_PER_POINT_LIGHT);

// Per-scene constants (one record in a storage buffer).
// The largest round float: the shaders' "no hit" distance (RT_FAR) and
// "no limit" in GpuSceneInfo::indirectClamp. Finite, because a driver may
// assume no infinities in arithmetic (fast-math).
#define RT_FAR_VALUE 3.0e38f

// GpuSceneInfo::soleInstance when the top level is not a lone mesh instance.
#define RT_NO_INSTANCE 0xffffffffu

// The lightest weight anything is traced at: GpuSceneInfo::branchBailout's
// floor (`--bailout 0`, the path tracer), where a branch's weight is rounding
// noise, and the transmittance below which glass blocks a shadow ray.
#define RT_MIN_BRANCH_WEIGHT 1e-4f

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
  uint areaLightCount;
  uint distributedBounces;  // Phong mode: sampled diffuse bounces besides the Whitted tree
  // Ambient light: this times the diffuse colour at every hit (family B's
  // conventions, a scene's `ambientlight`).
  vec3 ambient;
  // Largest channel one light contribution may add after a diffuse bounce
  // (`clampindirect`, firefly clamp; RT_FAR_VALUE: off).
  float indirectClamp;
  // 1: a hit's own light is clamped to 1, then weighted by
  // 1 - reflectivity - transmission (family B); 0: added to the reflection.
  uint mirrorsReplaceLocalLight;
  uint areaLightSamples;  // shadow rays per hit to all area lights together
  // When the whole top level is one mesh instance (a model file rendered
  // alone): that instance, whose root copy (node 1 + it) every walk starts
  // at, skipping a top-level node and leaf; RT_NO_INSTANCE otherwise
  // (traverse_bvh.glsl).
  uint soleInstance;
  // Ray-tree branches lighter than this are not traced (RenderSettings::
  // branchBailout; integrator.glsl addContinuation).
  float branchBailout;
};
RT_ASSERT_STD430_SIZE(GpuSceneInfo, 176);

// Push constants of one dispatch of the render kernel.
struct GpuFrameParams {
  uvec2 tileOrigin;  // first pixel of the dispatched tile
  uvec2 tileSize;    // pixels covered by the dispatch
  // Workgroup g of the dispatch renders block (g * stride) mod groups of the
  // tile, per axis (strides coprime with the group counts): CPU drivers give
  // each worker thread one contiguous range of workgroups (lavapipe: groups /
  // threads each), which the strides spread over the whole tile, so that an
  // expensive region (glass) does not fall to one thread while the other waits.
  uvec2 groupStride;
  uint sampleBegin;   // first sample index this dispatch adds
  uint sampleCount;   // samples per pixel this dispatch adds
  uint samplesTotal;  // total samples the render aims for (stratification)
  uint seed;
  uint samplerKind;
  uint pad0;
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

// The adaptive tiles covering an image of `size` pixels: (tiles per row,
// rows); tiles are numbered row-major over the whole image.
RT_SHARED_FUNCTION uvec2 adaptiveTileGrid(uvec2 size) {
  const uint tile = uint(RT_ADAPTIVE_TILE_SIZE);
  return (size + uvec2(tile - 1u)) / tile;
}

// Adaptive sampling's first round gives a second sample to two of the eight
// 4x2 blocks of every 8x8 tile, so that each tile's noise is measured from
// 16 pairs at 1.25 samples a pixel (AdaptiveSampling.hpp). Blocks, not
// single pixels: a 4x2 block is one run of eight invocations (pixelInGroup
// in trace.comp), one SIMD vector on lavapipe, which runs its loop until its
// slowest lane is done; one pixel in four of every vector with two samples
// made the first round as slow as two samples everywhere. Which two blocks
// is a hash of the tile, so no pattern repeats with the tiles: their
// indices, row-major over the tile's blocks. The host and the kernel share
// this definition.
RT_SHARED_FUNCTION uvec2 adaptivePairedBlocks(uint tileX, uint tileY) {
  uint h = tileX * 0x9E3779B1u ^ tileY * 0x85EBCA77u;
  h ^= h >> 15u;
  h *= 0x2C1B3C6Du;
  h ^= h >> 13u;
  uint first = h >> 29u;
  return uvec2(first, first ^ (1u + ((h >> 26u) & 3u)));
}

// 1 for a pixel of one of its tile's paired blocks, else 0.
RT_SHARED_FUNCTION uint adaptivePairedPixel(uint x, uint y) {
  uvec2 paired = adaptivePairedBlocks(x / RT_ADAPTIVE_TILE_SIZE, y / RT_ADAPTIVE_TILE_SIZE);
  const uint blocksPerRow = RT_ADAPTIVE_TILE_SIZE / RT_ADAPTIVE_PAIR_BLOCK_WIDTH;
  uint block = (y % RT_ADAPTIVE_TILE_SIZE) / RT_ADAPTIVE_PAIR_BLOCK_HEIGHT * blocksPerRow +
               (x % RT_ADAPTIVE_TILE_SIZE) / RT_ADAPTIVE_PAIR_BLOCK_WIDTH;
  return (block == paired.x || block == paired.y) ? 1u : 0u;
}

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_GPU_TYPES_H
