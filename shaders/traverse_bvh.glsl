// The walk over the renderer's own two-level BVH (see GpuBvhNode in
// gpu_types.h), for closest-hit and any-hit queries (traverse.glsl).
//
// Shaped for SIMD drivers that run every loop until its last lane is done,
// as lavapipe does: the cost of a loop is its body times the iterations of
// the slowest lane, and texel fetches (about 2 ns per lane each) dominate a
// body. A two-loop walk (Aila and Laine's while-while): an inner loop visits
// interior nodes only (one node, two fetches, per iteration) until every
// lane holds a leaf or is done; the outer loop tests the leaf. The inner
// loop branches on the two box tests: on Mesa 25 that measured 1.01-1.09x
// the branchless select-and-store form that Mesa 22.3 (which ran both sides
// of every branch) wanted (bunny primary, default.json, the common scene and
// the area-light study; bench/README.md). Both levels of the BVH share the two loops: a
// leaf says whether it holds mesh triangles or one top-level item, and
// entering a mesh built in world space only moves to its root. Each leaf
// carries only the code of the kinds the scene has (RT_FEATURE_*). 1.4x the
// bunny's primary rays per CPU-second of the walk before it, which rebuilt
// the ray and tested every kind at every leaf; 1.8x a walk with its own loop
// per mesh inside the top-level one (bench/README.md).
#ifndef RT_TRAVERSE_BVH_GLSL
#define RT_TRAVERSE_BVH_GLSL

#include "hits.glsl"
#ifdef RT_FEATURE_ALPHA_CUTOUTS
#include "alpha.glsl"
#endif

#ifdef RT_LANE_VOTES
#extension GL_KHR_shader_subgroup_vote : require
#endif

// Reciprocal direction with zero components replaced by a tiny signed value,
// so the slab test never computes 0 * inf = NaN.
vec3 safeReciprocal(vec3 d) {
  const float tiny = 1e-30;
  vec3 magnitude = max(abs(d), vec3(tiny));
  return vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0) / magnitude;
}

// min and max as a compare and a select: one x86 instruction each, where
// lavapipe builds GLSL's min and max (which must return the other operand
// when one is NaN) from three. The slab test's NaN cases (0 * inf) are kept
// out by safeReciprocal; a NaN slab still misses, as before.
float selectMin(float a, float b) { return a < b ? a : b; }
float selectMax(float a, float b) { return a > b ? a : b; }

// Entry distance of the ray into the box, or RT_FAR when it misses (tMin, tMax).
// `originTimesInv` is origin * invDir: one fused multiply-add per slab.
float boxEntry(vec3 boundsMin, vec3 boundsMax, vec3 originTimesInv, vec3 invDir, float tMin,
               float tMax) {
  vec3 t0 = fma(boundsMin, invDir, -originTimesInv);
  vec3 t1 = fma(boundsMax, invDir, -originTimesInv);
  bvec3 ascending = lessThan(t0, t1);
  vec3 near = mix(t1, t0, ascending);
  vec3 far = mix(t0, t1, ascending);
  float enter = selectMax(selectMax(near.x, near.y), selectMax(near.z, tMin));
  float exit = selectMin(selectMin(far.x, far.y), selectMin(far.z, tMax));
  // Widen by a few ulps: the float slab test may otherwise miss a primitive
  // lying exactly on the box face (robust traversal, as in pbrt-v4).
  return enter <= exit * 1.0000004 ? enter : RT_FAR;
}

bool isLeafRef(uint ref) { return (ref & RT_REF_LEAF) != 0u; }

// A ray as the walk tests it: the slab test's reciprocal direction and
// origin times it, and the watertight triangle test's frame, once per ray
// (and per instance entered).
struct WalkRay {
  Ray ray;
  vec3 invDir;
  vec3 originTimesInv;
  ShearedRay frame;
};

WalkRay walkRay(Ray ray) {
  vec3 invDir = safeReciprocal(ray.direction);
  return WalkRay(ray, invDir, ray.origin * invDir, shearRay(ray.direction));
}

// An interior node's two children: their boxes and references.
struct ChildBoxes {
  vec3 leftMin;
  vec3 leftMax;
  vec3 rightMin;
  vec3 rightMax;
  uint left;
  uint right;
};

ChildBoxes loadChildBoxes(uint node) {
  uvec4 low = nodeRow(node, 0u);
  uvec4 high = nodeRow(node, 1u);
  vec2 lminZmaxX = unpackHalf2x16(low.w);
  vec2 rminZmaxX = unpackHalf2x16(high.z);
  return ChildBoxes(vec3(unpackHalf2x16(low.z), lminZmaxX.x),
                    vec3(lminZmaxX.y, unpackHalf2x16(high.x)),
                    vec3(unpackHalf2x16(high.y), rminZmaxX.x),
                    vec3(rminZmaxX.y, unpackHalf2x16(high.w)), low.x, low.y);
}

// Entry distances of `ray` into both children (RT_FAR: missed).
vec2 childEntries(ChildBoxes boxes, WalkRay ray, float tMin, float tMax) {
  return vec2(boxEntry(boxes.leftMin, boxes.leftMax, ray.originTimesInv, ray.invDir, tMin, tMax),
              boxEntry(boxes.rightMin, boxes.rightMax, ray.originTimesInv, ray.invDir, tMin,
                       tMax));
}

#ifdef RT_FEATURE_MESHES
// A mesh triangle of `instance` against `ray`; on a hit shrinks tMax and
// records it in `hit`. Normals are found once, after the walk: the leaf
// loop runs for every lane, so it carries as little as it can. With alpha
// cutouts a hit in a hole is no hit (`worldRay` decides BLEND's coin).
bool testMeshTriangle(uint item, vec3 v0, vec3 v1, vec3 v2, WalkRay ray, Ray worldRay,
                      float tMin, inout float tMax, uint instance, inout SurfaceHit hit) {
  vec2 barycentric;
  float t = tMax;
  if (!intersectTriangleSheared(v0, v1, v2, ray.ray.origin, ray.frame, tMin, t, barycentric)) {
    return false;
  }
#ifdef RT_FEATURE_ALPHA_CUTOUTS
  if (!alphaCovers(instance, item, barycentric, worldRay)) return false;
#endif
  tMax = t;
  hit.t = t;
  hit.primitiveIndex = instance;
  hit.triangleIndex = item;
  hit.barycentric = barycentric;
  return true;
}
#endif

#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
// Stack entry that ends a mesh instance: the walk goes back to world space.
// Only scenes with a mesh placed more than once need it: a mesh used once is
// built in world space, where the ray already is.
const uint RT_REF_LEAVE_INSTANCE = RT_REF_LEAF | RT_REF_MESH;
#endif

// The walk's stack: the top four entries in registers, the rest in an array
// that only deep paths touch. A SIMD driver writes an array at per-lane
// indices lane by lane, behind a branch per lane; moving registers is one
// select each. The bunny's primary rays and the common scene: 1.03-1.07x
// the walk with the whole stack in the array (bench/README.md).
// Lavapipe runs that lane-by-lane store whenever the push runs at all, for
// every lane, each lane's mask bit a branch that the CPU mispredicts (10% of
// the common scene's kernel time in one walk's store): a vote
// (RT_LANE_VOTES) skips it unless some lane spills, and scenes whose walks
// never hold more than the registers' four entries
// (RT_BVH_STACK_IN_REGISTERS, most coursework scenes) are built without the
// array. Together the common scene 1.06x (pinhole) and 1.16x (thin lens),
// `default.json` 1.35x, the thin-lens study 1.28x (bench/README.md).
// The array's read on a pop measured no better behind a vote (0.93-1.06x):
// it is a gather without branches.
#if RT_BVH_STACK_REGISTERS != 4
#error pushTop and popTop move four registers
#endif
struct StackTop {
  uint entries[RT_BVH_STACK_REGISTERS];  // [0] is the top
  uint size;                             // entries in all, registers and array
};

// Pushes `node`; returns the entry that leaves the registers for the array
// slot size - 5 when more than four are held.
uint pushTop(inout StackTop top, uint node) {
  uint spilled = top.entries[3];
  top.entries[3] = top.entries[2];
  top.entries[2] = top.entries[1];
  top.entries[1] = top.entries[0];
  top.entries[0] = node;
  ++top.size;
  return spilled;
}

// Pops the top entry (RT_NONE when empty); the caller refills entries[3]
// from array slot size - 4 when at least four remain.
uint popTop(inout StackTop top) {
  uint node = top.size > 0u ? top.entries[0] : RT_NONE;
  top.entries[0] = top.entries[1];
  top.entries[1] = top.entries[2];
  top.entries[2] = top.entries[3];
  top.size = top.size > 0u ? top.size - 1u : 0u;
  return node;
}

#ifdef RT_LANE_VOTES
#define RT_ANY_LANE(condition) subgroupAny(condition)
#else
#define RT_ANY_LANE(condition) (condition)
#endif
#ifdef RT_BVH_STACK_IN_REGISTERS
#define RT_PUSH(top, spill, node) \
  { pushTop(top, node); }
#define RT_POP(top, spill, node) \
  { node = popTop(top); }
#else
#define RT_PUSH(top, spill, node)                 \
  {                                               \
    uint leaving = pushTop(top, node);            \
    bool spills = top.size > 4u;                  \
    if (RT_ANY_LANE(spills)) {                    \
      if (spills) spill[top.size - 5u] = leaving; \
    }                                             \
  }
#define RT_POP(top, spill, node)                               \
  {                                                            \
    node = popTop(top);                                        \
    if (top.size >= 4u) top.entries[3] = spill[top.size - 4u]; \
  }
#endif
// From an interior node to its nearer child that the ray enters (the other
// one pushed if it enters both), or to the stack's top if it enters neither.
// `entries` is childEntries' answer.
#define RT_DESCEND(top, spill, node, boxes, entries)                     \
  {                                                                      \
    bool hitLeft = entries.x != RT_FAR, hitRight = entries.y != RT_FAR; \
    if (!hitLeft && !hitRight) {                                         \
      RT_POP(top, spill, node);                                          \
    } else {                                                             \
      bool leftFirst = entries.x <= entries.y;                           \
      node = leftFirst ? boxes.left : boxes.right;                       \
      if (hitLeft && hitRight) RT_PUSH(top, spill, leftFirst ? boxes.right : boxes.left); \
    }                                                                    \
  }

// After a leaf: a mesh instance's leaf goes on at the copy of the mesh's
// root, node 1 + item, above the entries waiting on the stack (`enter`,
// declared here, says so; `instance` becomes that mesh); any other leaf
// goes back to the stack's top. Both walks leave their leaves this way.
#ifdef RT_FEATURE_MESHES
#define RT_LEAVE_LEAF(top, spill, node, instance, enter, meshLeaf, kind, first) \
  bool enter = !meshLeaf && kind == RT_PRIM_INSTANCE;                          \
  if (enter) {                                                                 \
    node = 1u + first;                                                         \
  } else {                                                                     \
    RT_POP(top, spill, node);                                                  \
  }                                                                            \
  instance = enter ? first : instance
#else
#define RT_LEAVE_LEAF(top, spill, node, instance, enter, meshLeaf, kind, first) \
  RT_POP(top, spill, node)
#endif

// Walks the BVH; with anyHit it stops at the first intersection found.
// A walk pushes only when it enters both children, at most one entry per
// level of its path; RT_BVH_STACK_SIZE is over twice RT_BVH_MAX_DEPTH, room
// for a top-level path, the instance marker and a mesh path without a check.
bool traverse(Ray worldRay, float tMin, inout float tMax, bool anyHit, out SurfaceHit hit) {
  clearHit(hit);
#ifdef RT_TALLY_RAYS
  ++raysTraced;
#endif
  if (sceneInfo.bvhNodeCount == 0u) return false;
  WalkRay ray = walkRay(worldRay);
  uint hitKind = RT_PRIM_TRIANGLE;
  StackTop top = StackTop(uint[4](RT_NONE, RT_NONE, RT_NONE, RT_NONE), 0u);
  uint spill[RT_BVH_STACK_SIZE];
  uint node = 0u;  // a node, a leaf reference, or RT_NONE: done
#ifdef RT_FEATURE_MESHES
  // The last instance entered: mesh nodes are reached only through it (the
  // stack holds a mesh's entries above those that were there before). A lone
  // instance is entered at once: the bunny's primary rays 1.06x (bench/README.md).
  uint instance = sceneInfo.soleInstance;
  if (instance != RT_NO_INSTANCE) node = 1u + instance;
#endif
  while (node != RT_NONE) {
    // Interior nodes until this lane holds a leaf (or has nothing left).
    while (!isLeafRef(node)) {
      ChildBoxes boxes = loadChildBoxes(node);
      vec2 entries = childEntries(boxes, ray, tMin, tMax);
      RT_DESCEND(top, spill, node, boxes, entries);
    }
    if (node == RT_NONE) break;

    // A leaf (see GpuBvhNode): `count` mesh triangles, or one top-level
    // item of the kind it names (stored plus one: 0 is the empty leaf).
    uint first = node & RT_REF_FIRST_MASK;
    uint field = (node >> RT_REF_COUNT_SHIFT) & RT_REF_MAX_LEAF_SIZE;
    bool meshLeaf = (node & RT_REF_MESH) != 0u;
    uint kind = field - 1u;
#ifdef RT_FEATURE_MESHES
    uint count = meshLeaf ? field : 0u;
    for (uint item = first; item < first + count; ++item) {
      if (testMeshTriangle(item, itemRow(item, 0u).xyz, itemRow(item, 1u).xyz,
                           itemRow(item, 2u).xyz, ray, worldRay, tMin, tMax, instance, hit)) {
        hitKind = RT_PRIM_TRIANGLE;
        if (anyHit) return true;
      }
    }
#endif
#ifdef RT_TOP_LEVEL_SHAPES
    if (!meshLeaf && testTopLevelItem(first, kind, ray.ray, ray.frame, tMin, tMax, hit)) {
      hitKind = kind;
      if (anyHit) return true;
    }
#endif
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
    bool leave = node == RT_REF_LEAVE_INSTANCE;
#endif
    RT_LEAVE_LEAF(top, spill, node, instance, enter, meshLeaf, kind, first);
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
    // In object space until the marker under the mesh's entries comes back.
    if (enter) {
      RT_PUSH(top, spill, RT_REF_LEAVE_INSTANCE);
      ray = walkRay(
          rayToObject(worldRay, itemRow(first, 0u), itemRow(first, 1u), itemRow(first, 2u)));
    }
    if (leave) ray = walkRay(worldRay);
#endif
  }
  if (hit.t < 0.0) return false;
  completeHitNormal(worldRay, hitKind, hit);
  return true;
}


#if defined(RT_SHADOW_PAIRS) || defined(RT_PRIMARY_PAIRS)
// Two rays walked together: the shadow rays of one shading point towards
// two light samples, or the primary rays of two samples of one pixel, start
// at one point and mostly head the same way, so they visit mostly the same
// nodes, and each node's two texel fetches (the larger part of a visit on
// lavapipe) serve both. A node is entered if
// either ray enters it, nearest first by the nearer of the two. The answers
// are those of two `traverse` calls: each ray keeps its own tMax and hit,
// and an any-hit ray that found one stops taking part. A ray that is not
// `walking` takes no part and is not counted. tMin is 0 (shadow rays), so a
// negative tMax meets nothing. Not built with instance transforms.
#ifdef RT_FEATURE_INSTANCE_TRANSFORMS
#error paired walks are built without instance transforms
#endif
void traversePair(Ray rayA, Ray rayB, bvec2 walking, vec2 tMax, bool anyHit,
                  out SurfaceHit hitA, out SurfaceHit hitB) {
  clearHit(hitA);
  clearHit(hitB);
  const float tMin = 0.0;
  const float retired = -1.0;  // below tMin: no box or primitive is met
  tMax = mix(vec2(retired), tMax, walking);
#ifdef RT_TALLY_RAYS
  raysTraced += uint(walking.x) + uint(walking.y);
#endif
  if (sceneInfo.bvhNodeCount == 0u || !any(walking)) return;
  WalkRay a = walkRay(rayA);
  WalkRay b = walkRay(rayB);
  uint kindA = RT_PRIM_TRIANGLE, kindB = RT_PRIM_TRIANGLE;
  StackTop top = StackTop(uint[4](RT_NONE, RT_NONE, RT_NONE, RT_NONE), 0u);
  uint spill[RT_BVH_STACK_SIZE];
  uint node = 0u;
#ifdef RT_FEATURE_MESHES
  uint instance = sceneInfo.soleInstance;
  if (instance != RT_NO_INSTANCE) node = 1u + instance;
#endif
  while (node != RT_NONE) {
    while (!isLeafRef(node)) {
      ChildBoxes boxes = loadChildBoxes(node);
      vec2 entriesA = childEntries(boxes, a, tMin, tMax.x);
      vec2 entriesB = childEntries(boxes, b, tMin, tMax.y);
      vec2 entries = vec2(selectMin(entriesA.x, entriesB.x), selectMin(entriesA.y, entriesB.y));
      RT_DESCEND(top, spill, node, boxes, entries);
    }
    if (node == RT_NONE) break;
    uint first = node & RT_REF_FIRST_MASK;
    uint field = (node >> RT_REF_COUNT_SHIFT) & RT_REF_MAX_LEAF_SIZE;
    bool meshLeaf = (node & RT_REF_MESH) != 0u;
    uint kind = field - 1u;
#ifdef RT_FEATURE_MESHES
    uint count = meshLeaf ? field : 0u;
    for (uint item = first; item < first + count; ++item) {
      vec3 v0 = itemRow(item, 0u).xyz, v1 = itemRow(item, 1u).xyz, v2 = itemRow(item, 2u).xyz;
      if (testMeshTriangle(item, v0, v1, v2, a, rayA, tMin, tMax.x, instance, hitA)) {
        kindA = RT_PRIM_TRIANGLE;
        if (anyHit) tMax.x = retired;
      }
      if (testMeshTriangle(item, v0, v1, v2, b, rayB, tMin, tMax.y, instance, hitB)) {
        kindB = RT_PRIM_TRIANGLE;
        if (anyHit) tMax.y = retired;
      }
    }
#endif
#ifdef RT_TOP_LEVEL_SHAPES
    if (!meshLeaf) {
      if (testTopLevelItem(first, kind, a.ray, a.frame, tMin, tMax.x, hitA)) {
        kindA = kind;
        if (anyHit) tMax.x = retired;
      }
      if (testTopLevelItem(first, kind, b.ray, b.frame, tMin, tMax.y, hitB)) {
        kindB = kind;
        if (anyHit) tMax.y = retired;
      }
    }
#endif
    if (anyHit && tMax.x == retired && tMax.y == retired) break;
    RT_LEAVE_LEAF(top, spill, node, instance, enter, meshLeaf, kind, first);
  }
  if (anyHit) return;
  if (hitA.t >= 0.0) completeHitNormal(rayA, kindA, hitA);
  if (hitB.t >= 0.0) completeHitNormal(rayB, kindB, hitB);
}
#endif

#endif
