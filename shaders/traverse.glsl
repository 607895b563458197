// Scene queries over the two-level BVH (see GpuBvhNode in gpu_types.h):
// closest hit and any hit (shadows).
//
// Shaped for SIMD drivers that run every branch of a loop body for all
// lanes (masked), every loop body at least once and every loop until its
// last lane is done, as lavapipe (Mesa 22.3) does: the cost of a loop is its
// body times the iterations of the slowest lane, and texel fetches (about
// 2 ns per lane each) dominate a body. A two-loop walk (Aila and Laine's
// while-while): an inner loop visits interior nodes only (one node, two
// fetches, per iteration) until every lane holds a leaf or is done; the
// outer loop tests the leaf. Both levels of the BVH share the two loops: a
// leaf says whether it holds mesh triangles or one top-level item, and
// entering a mesh built in world space only moves to its root. Each leaf
// carries only the code of the kinds the scene has (RT_FEATURE_*). 1.4x the
// bunny's primary rays per CPU-second of the walk before it, which rebuilt
// the ray and tested every kind at every leaf; 1.8x a walk with its own loop
// per mesh inside the top-level one (README "Benchmarks").
#ifndef RT_TRAVERSE_GLSL
#define RT_TRAVERSE_GLSL

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

// Reciprocal direction with zero components replaced by a tiny signed value,
// so the slab test never computes 0 * inf = NaN.
vec3 safeReciprocal(vec3 d) {
  const float tiny = 1e-30;
  vec3 magnitude = max(abs(d), vec3(tiny));
  return vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0) / magnitude;
}

// Entry distance of the ray into the box, or RT_FAR when it misses (tMin, tMax).
// `originTimesInv` is origin * invDir: one fused multiply-add per slab.
float boxEntry(vec3 boundsMin, vec3 boundsMax, vec3 originTimesInv, vec3 invDir, float tMin,
               float tMax) {
  vec3 t0 = fma(boundsMin, invDir, -originTimesInv);
  vec3 t1 = fma(boundsMax, invDir, -originTimesInv);
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, tMin));
  float exit = min(min(far.x, far.y), min(far.z, tMax));
  // Widen by a few ulps: the float slab test may otherwise miss a primitive
  // lying exactly on the box face (robust traversal, as in pbrt-v4).
  return enter <= exit * 1.0000004 ? enter : RT_FAR;
}

bool isLeafRef(uint ref) { return (ref & RT_REF_LEAF) != 0u; }

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

#ifdef RT_COUNT_RAYS
uint raysTraced = 0u;  // rays this invocation traced, for benchmarks
#endif

#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
// Stack entry that ends a mesh instance: the walk goes back to world space.
// Only scenes with a mesh placed more than once need it: a mesh used once is
// built in world space, where the ray already is.
const uint RT_REF_LEAVE_INSTANCE = RT_REF_LEAF | RT_REF_MESH;
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

#ifdef RT_ACCEL_HARDWARE
#include "traverse_hardware.glsl"
#else
// Walks the BVH; with anyHit it stops at the first intersection found.
// A walk pushes only when it enters both children, at most one entry per
// level of its path; RT_BVH_STACK_SIZE is over twice RT_BVH_MAX_DEPTH, room
// for a top-level path, the instance marker and a mesh path without a check.
bool traverse(Ray worldRay, float tMin, inout float tMax, bool anyHit, out SurfaceHit hit) {
  clearHit(hit);
#ifdef RT_COUNT_RAYS
  ++raysTraced;
#endif
  if (sceneInfo.bvhNodeCount == 0u) return false;
  Ray ray = worldRay;
  vec3 invDir = safeReciprocal(ray.direction);
  vec3 originTimesInv = ray.origin * invDir;
  // The watertight test's ray frame, once per ray (and per instance entered).
  ShearedRay frame = shearRay(ray.direction);
  uint hitKind = RT_PRIM_TRIANGLE;
  uint stack[RT_BVH_STACK_SIZE + 1u];  // one spare slot above the top for branchless pushes
  uint stackSize = 0u;
#ifdef RT_FEATURE_MESHES
  // The last instance entered: mesh nodes are reached only through it (the
  // stack holds a mesh's entries above those that were there before).
  uint instance = RT_NONE;
#endif
  uint node = 0u;  // a node, a leaf reference, or RT_NONE: done
  while (node != RT_NONE) {
    // Interior nodes until this lane holds a leaf (or has nothing left).
    // Branchless: the store above the top is always made and kept only by
    // a push, the top is always read and used only by a pop.
    while (!isLeafRef(node)) {
      uvec4 low = nodeRow(node, 0u);
      uvec4 high = nodeRow(node, 1u);
      vec2 lminZmaxX = unpackHalf2x16(low.w);
      vec2 rminZmaxX = unpackHalf2x16(high.z);
      vec3 leftMin = vec3(unpackHalf2x16(low.z), lminZmaxX.x);
      vec3 leftMax = vec3(lminZmaxX.y, unpackHalf2x16(high.x));
      vec3 rightMin = vec3(unpackHalf2x16(high.y), rminZmaxX.x);
      vec3 rightMax = vec3(rminZmaxX.y, unpackHalf2x16(high.w));
      float tLeft = boxEntry(leftMin, leftMax, originTimesInv, invDir, tMin, tMax);
      float tRight = boxEntry(rightMin, rightMax, originTimesInv, invDir, tMin, tMax);
      bool leftFirst = tLeft <= tRight;
      bool descend = min(tLeft, tRight) != RT_FAR;
      stack[stackSize] = leftFirst ? low.y : low.x;
      stackSize += max(tLeft, tRight) != RT_FAR ? 1u : 0u;
      bool pop = !descend && stackSize > 0u;
      uint top = stack[max(stackSize, 1u) - 1u];
      node = descend ? (leftFirst ? low.x : low.y) : (pop ? top : RT_NONE);
      stackSize -= pop ? 1u : 0u;
    }
    if (node == RT_NONE) break;

    // A leaf (see GpuBvhNode): `count` mesh triangles, or one top-level
    // item of the kind it names (stored plus one: 0 is the empty leaf).
    uint first = node & RT_REF_FIRST_MASK;
    uint field = (node >> RT_REF_COUNT_SHIFT) & RT_REF_MAX_LEAF_SIZE;
    bool meshLeaf = (node & RT_REF_MESH) != 0u;
    uint kind = field - 1u;
#ifdef RT_FEATURE_MESHES
    // Normals are found once, after the walk: the loop body runs for every
    // lane, so it carries as little as it can.
    uint count = meshLeaf ? field : 0u;
    for (uint item = first; item < first + count; ++item) {
      vec2 barycentric;
      if (intersectTriangleSheared(itemRow(item, 0u).xyz, itemRow(item, 1u).xyz,
                                   itemRow(item, 2u).xyz, ray.origin, frame, tMin, tMax,
                                   barycentric)) {
        hit.t = tMax;
        hit.primitiveIndex = instance;
        hit.triangleIndex = item;
        hit.barycentric = barycentric;
        hitKind = RT_PRIM_TRIANGLE;
        if (anyHit) return true;
      }
    }
#endif
#ifdef RT_TOP_LEVEL_SHAPES
    if (!meshLeaf && testTopLevelItem(first, kind, ray, frame, tMin, tMax, hit)) {
      hitKind = kind;
      if (anyHit) return true;
    }
#endif
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
    bool leave = node == RT_REF_LEAVE_INSTANCE;
#endif
    node = stackSize > 0u ? stack[--stackSize] : RT_NONE;
#ifdef RT_FEATURE_MESHES
    // A mesh instance: the entry just popped waits again (it is still in
    // its slot), and the walk goes on at the copy of the mesh's root, node
    // 1 + item.
    bool enter = !meshLeaf && kind == RT_PRIM_INSTANCE;
    stackSize += enter && node != RT_NONE ? 1u : 0u;
    node = enter ? 1u + first : node;
    instance = enter ? first : instance;
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
    // In object space until the marker under the mesh's entries comes back.
    if (enter) {
      stack[stackSize++] = RT_REF_LEAVE_INSTANCE;
      ray = rayToObject(worldRay, itemRow(first, 0u), itemRow(first, 1u), itemRow(first, 2u));
    }
    if (leave) ray = worldRay;
    if (enter || leave) {
      invDir = safeReciprocal(ray.direction);
      originTimesInv = ray.origin * invDir;
      frame = shearRay(ray.direction);
    }
#endif
#endif
  }
  if (hit.t < 0.0) return false;
  completeHitNormal(worldRay, hitKind, hit);
  return true;
}
#endif  // RT_ACCEL_HARDWARE

bool closestHit(Ray ray, float tMin, float tMax, out SurfaceHit hit) {
  return traverse(ray, tMin, tMax, false, hit);
}

bool occluded(Ray ray, float tMin, float tMax) {
  SurfaceHit ignored;
  return traverse(ray, tMin, tMax, true, ignored);
}

#endif
