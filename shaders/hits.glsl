// What the scene queries find and the pieces both walks share: the hit
// record, the leaf tests of top-level shapes, the normal found after a
// walk (traverse_bvh.glsl, traverse_hardware.glsl).
#ifndef RT_HITS_GLSL
#define RT_HITS_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "intersect.glsl"

// "No hit" distance (see RT_FAR_VALUE in gpu_types.h).
const float RT_FAR = RT_FAR_VALUE;

const uint RT_NONE = 0xffffffffu;

struct SurfaceHit {
  float t;
  uint primitiveIndex;  // top-level primitive hit: a shape's primitive or a mesh instance
  uint triangleIndex;   // instances: the mesh triangle's item; RT_NONE otherwise
  vec3 normal;          // outward geometric normal, world space
  vec2 barycentric;     // triangles: weights of v1 and v2
};

// Material and scene shape of a hit: mesh triangles take them from their
// instance, every other primitive carries its own.
uint hitMaterial(SurfaceHit hit) { return primitiveInfo(hit.primitiveIndex).y; }
uint hitShape(SurfaceHit hit) { return primitiveInfo(hit.primitiveIndex).z; }

#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
// Point and direction through the world-to-object rows of an instance. The
// direction is not renormalised, so distances t mean the same in both spaces.
Ray rayToObject(Ray ray, vec4 row0, vec4 row1, vec4 row2) {
  vec4 p = vec4(ray.origin, 1.0);
  return Ray(vec3(dot(row0, p), dot(row1, p), dot(row2, p)),
             vec3(dot(row0.xyz, ray.direction), dot(row1.xyz, ray.direction),
                  dot(row2.xyz, ray.direction)));
}

// Object normal to world: the transpose of the world-to-object matrix is the
// inverse transpose of object-to-world, which keeps outward normals outward.
vec3 normalToWorld(uint instance, vec3 objectNormal) {
  return normalize(itemRow(instance, 0u).xyz * objectNormal.x +
                   itemRow(instance, 1u).xyz * objectNormal.y +
                   itemRow(instance, 2u).xyz * objectNormal.z);
}
#endif

// Rays this invocation traced: for benchmarks (RT_COUNT_RAYS) and for
// adaptive sampling, which weighs each tile's samples by their rays.
#if defined(RT_COUNT_RAYS) || defined(RT_ADAPTIVE_SAMPLING)
#define RT_TALLY_RAYS
uint raysTraced = 0u;
#endif


// Leaf items are tested where the top level and the meshes need different
// code: these kinds are single top-level items.
#if defined(RT_FEATURE_SPHERES) || defined(RT_FEATURE_CYLINDERS) || \
    defined(RT_FEATURE_LOOSE_TRIANGLES)
#define RT_TOP_LEVEL_SHAPES
#endif

#ifdef RT_TOP_LEVEL_SHAPES
// One top-level item of `kind` (not a mesh instance); on a hit shrinks tMax
// and records the item in `hit`.
bool testTopLevelItem(uint item, uint kind, Ray ray, ShearedRay frame, float tMin,
                      inout float tMax, inout SurfaceHit hit) {
  vec4 row0 = itemRow(item, 0u);
  vec4 row1 = itemRow(item, 1u);
  vec2 barycentric = vec2(0.0);
  bool found = false;
#ifdef RT_FEATURE_LOOSE_TRIANGLES
  if (kind == RT_PRIM_TRIANGLE) {
    found = intersectTriangleSheared(row0.xyz, row1.xyz, itemRow(item, 2u).xyz, ray.origin,
                                     frame, tMin, tMax, barycentric);
  }
#endif
#ifdef RT_FEATURE_SPHERES
  vec3 unusedNormal;
  if (kind == RT_PRIM_SPHERE) {
    found = intersectSphere(row0.xyz, row0.w, ray, tMin, tMax, unusedNormal);
  }
#endif
#ifdef RT_FEATURE_CYLINDERS
  vec3 cylinderNormal = vec3(0.0, 0.0, 1.0);
  if (kind == RT_PRIM_CYLINDER) {
    found = intersectCylinder(row0.xyz, row1.xyz, row0.w, row1.w, ray, tMin, tMax,
                              cylinderNormal);
  }
  if (found) hit.normal = cylinderNormal;
#endif
  if (found) {
    hit.t = tMax;
    hit.primitiveIndex = item;
    hit.triangleIndex = RT_NONE;
    hit.barycentric = barycentric;
  }
  return found;
}
#endif

// The outward normal of a hit found by either walk, once after it: the
// walks carry as little per candidate as they can. Cylinders found theirs.
void completeHitNormal(Ray worldRay, uint hitKind, inout SurfaceHit hit) {
  uint hitItem = hit.triangleIndex != RT_NONE ? hit.triangleIndex : hit.primitiveIndex;
  vec4 row0 = itemRow(hitItem, 0u);
#ifdef RT_FEATURE_SPHERES
  if (hitKind == RT_PRIM_SPHERE) {
    hit.normal = normalize(worldRay.origin + hit.t * worldRay.direction - row0.xyz);
  }
#endif
#ifdef RT_FEATURE_TRIANGLES
  if (hitKind == RT_PRIM_TRIANGLE) {
    // Items hold the corners themselves (watertight intersection needs them).
    hit.normal = normalize(cross(itemRow(hitItem, 1u).xyz - row0.xyz, itemRow(hitItem, 2u).xyz - row0.xyz));
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
    if (hit.triangleIndex != RT_NONE) hit.normal = normalToWorld(hit.primitiveIndex, hit.normal);
#endif
  }
#endif
}

void clearHit(out SurfaceHit hit) {
  hit.t = -1.0;
  hit.primitiveIndex = 0u;
  hit.triangleIndex = RT_NONE;
  hit.normal = vec3(0.0, 0.0, 1.0);
  hit.barycentric = vec2(0.0);
}

#endif
