#version 460
// The plain reference kernel of PlainBvhKernel.hpp: one primary ray per
// invocation, a stack walk of Aila and Laine's binary layout (with
// PLAIN_BINARY_HALF in the renderer's two-texel half-float nodes; with
// PLAIN_WIDE, four-wide nodes), Moller-Trumbore triangles; writes the hit
// distance (-1: miss). Push constants only enter
// arithmetic, never a branch: lavapipe would recompile the kernel at every
// dispatch otherwise.
#ifdef PLAIN_REGISTER_STACK
#extension GL_KHR_shader_subgroup_vote : require
#endif
#ifdef PLAIN_DEVICE_ADDRESS
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#endif
layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform PlainParams {
  vec4 position;
  float tanHalfFovY;
  uint width;
  uint sampleIndex;
  uint pad;
  uvec2 nodeAddress;  // PLAIN_DEVICE_ADDRESS only
  uvec2 triangleAddress;
} params;

#ifdef PLAIN_DEVICE_ADDRESS
// Loads through buffer device addresses: no descriptor, no bounds check.
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Rows {
  vec4 rows[];
};
vec4 nodeRow(uint node, uint row) {
  return Rows(params.nodeAddress).rows[node * PLAIN_NODE_TEXELS + row];
}
vec4 triangleRow(uint triangle, uint row) {
  return Rows(params.triangleAddress).rows[triangle * 3u + row];
}
#elif defined(PLAIN_STORAGE_BUFFERS)
layout(std430, set = 0, binding = 0) readonly buffer Nodes { vec4 nodes[]; };
layout(std430, set = 0, binding = 1) readonly buffer Triangles { vec4 triangles[]; };
vec4 nodeRow(uint node, uint row) { return nodes[node * PLAIN_NODE_TEXELS + row]; }
vec4 triangleRow(uint triangle, uint row) { return triangles[triangle * 3u + row]; }
#elif defined(PLAIN_WIDE_HALF) || defined(PLAIN_BINARY_HALF)
layout(set = 0, binding = 0) uniform utextureBuffer halfNodeTexels;
layout(set = 0, binding = 1) uniform textureBuffer triangleTexels;
vec4 triangleRow(uint triangle, uint row) {
  return texelFetch(triangleTexels, int(triangle * 3u + row));
}
#else
layout(set = 0, binding = 0) uniform textureBuffer nodeTexels;
layout(set = 0, binding = 1) uniform textureBuffer triangleTexels;
vec4 nodeRow(uint node, uint row) {
  return texelFetch(nodeTexels, int(node * PLAIN_NODE_TEXELS + row));
}
vec4 triangleRow(uint triangle, uint row) {
  return texelFetch(triangleTexels, int(triangle * 3u + row));
}
#endif

layout(std430, set = 0, binding = 2) writeonly buffer Distances { float distances[]; };

const uint LEAF = 0x80000000u;
const uint DONE = 0xffffffffu;

// The walk's stack. With PLAIN_REGISTER_STACK as the renderer keeps it
// (shaders/traverse_bvh.glsl): the top four entries in registers, the rest
// in an array written only when some lane of the subgroup spills (lavapipe
// writes an array at per-lane indices lane by lane, a branch a lane); else
// the whole stack in the array.
#ifdef PLAIN_REGISTER_STACK
struct StackTop {
  uint e0, e1, e2, e3;
  uint size;
};
#define STACK_DECLARE                                   \
  StackTop top = StackTop(DONE, DONE, DONE, DONE, 0u); \
  uint spill[96]
#define STACK_PUSH(value)                              \
  {                                                    \
    uint leaving = top.e3;                             \
    top.e3 = top.e2;                                   \
    top.e2 = top.e1;                                   \
    top.e1 = top.e0;                                   \
    top.e0 = (value);                                  \
    ++top.size;                                        \
    bool spills = top.size > 4u;                       \
    if (subgroupAny(spills)) {                         \
      if (spills) spill[top.size - 5u] = leaving;      \
    }                                                  \
  }
#define STACK_POP(node)                                        \
  {                                                            \
    node = top.size > 0u ? top.e0 : DONE;                      \
    top.e0 = top.e1;                                           \
    top.e1 = top.e2;                                           \
    top.e2 = top.e3;                                           \
    top.size = top.size > 0u ? top.size - 1u : 0u;             \
    if (top.size >= 4u) top.e3 = spill[top.size - 4u];         \
  }
#else
#define STACK_DECLARE \
  uint stack[96];     \
  uint stackSize = 0u
#define STACK_PUSH(value) \
  { stack[stackSize++] = (value); }
#define STACK_POP(node) \
  { node = stackSize > 0u ? stack[--stackSize] : DONE; }
#endif

// Entry distance into the box [lo, hi] given per axis as (lo.x, hi.x, ...),
// or a miss (entry > exit).
vec2 slabs(vec2 x, vec2 y, vec2 z, vec3 invDir, vec3 originTimesInv, float tMax) {
  vec2 tx = x * invDir.x - originTimesInv.x;
  vec2 ty = y * invDir.y - originTimesInv.y;
  vec2 tz = z * invDir.z - originTimesInv.z;
  float entry = max(max(min(tx.x, tx.y), min(ty.x, ty.y)), max(min(tz.x, tz.y), 0.0));
  float exit = min(min(max(tx.x, tx.y), max(ty.x, ty.y)), min(max(tz.x, tz.y), tMax));
  return vec2(entry, exit);
}

#if defined(PLAIN_WIDE)
// Four children per node, structure of arrays: rows min x, max x, min y,
// max y, min z, max z of the four boxes, then the four child references;
// with PLAIN_WIDE_HALF the boxes are half floats in four texels a node (rows
// x, y, z: the four minima then the four maxima as half pairs; then the
// references), as many texels per child as the binary layout.
void sortPair(inout float da, inout uint ra, inout float db, inout uint rb) {
  bool swap = db < da;
  float d = swap ? db : da;
  uint r = swap ? rb : ra;
  db = swap ? da : db;
  rb = swap ? ra : rb;
  da = d;
  ra = r;
}

// The four boxes of `node` as min and max per axis (one child a component).
struct WideNode {
  vec4 minX, maxX, minY, maxY, minZ, maxZ;
  uvec4 refs;
};

#ifdef PLAIN_WIDE_HALF
vec4 halves4(uvec2 packed) { return vec4(unpackHalf2x16(packed.x), unpackHalf2x16(packed.y)); }

WideNode wideNode(uint node) {
  uvec4 x = texelFetch(halfNodeTexels, int(node * 4u));
  uvec4 y = texelFetch(halfNodeTexels, int(node * 4u + 1u));
  uvec4 z = texelFetch(halfNodeTexels, int(node * 4u + 2u));
  return WideNode(halves4(x.xy), halves4(x.zw), halves4(y.xy), halves4(y.zw), halves4(z.xy),
                  halves4(z.zw), texelFetch(halfNodeTexels, int(node * 4u + 3u)));
}
#else
WideNode wideNode(uint node) {
  return WideNode(nodeRow(node, 0u), nodeRow(node, 1u), nodeRow(node, 2u), nodeRow(node, 3u),
                  nodeRow(node, 4u), nodeRow(node, 5u), floatBitsToUint(nodeRow(node, 6u)));
}
#endif

float closestHit(vec3 origin, vec3 direction) {
  vec3 invDir = 1.0 / direction;
  vec3 originTimesInv = origin * invDir;
  float tMax = 1e30;
  STACK_DECLARE;
  uint node = 0u;
  const float MISS = 3e38;
  while (node != DONE) {
    while (node < LEAF) {
      WideNode wide = wideNode(node);
      uvec4 refs = wide.refs;
      vec4 t0x = wide.minX * invDir.x - originTimesInv.x;
      vec4 t1x = wide.maxX * invDir.x - originTimesInv.x;
      vec4 t0y = wide.minY * invDir.y - originTimesInv.y;
      vec4 t1y = wide.maxY * invDir.y - originTimesInv.y;
      vec4 t0z = wide.minZ * invDir.z - originTimesInv.z;
      vec4 t1z = wide.maxZ * invDir.z - originTimesInv.z;
      vec4 entry = max(max(min(t0x, t1x), min(t0y, t1y)), max(min(t0z, t1z), vec4(0.0)));
      vec4 exit = min(min(max(t0x, t1x), max(t0y, t1y)), min(max(t0z, t1z), vec4(tMax)));
      bvec4 enters = bvec4(uvec4(lessThanEqual(entry, exit)) & uvec4(notEqual(refs, uvec4(DONE))));
      vec4 d = mix(vec4(MISS), entry, enters);
      float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
      uint r0 = refs.x, r1 = refs.y, r2 = refs.z, r3 = refs.w;
      // Only the nearest child first; the others wait in any order (a full
      // sort of the four measured slower still).
      sortPair(d0, r0, d1, r1);
      sortPair(d0, r0, d2, r2);
      sortPair(d0, r0, d3, r3);
#ifdef PLAIN_REGISTER_STACK
      if (d3 < MISS) STACK_PUSH(r3);
      if (d2 < MISS) STACK_PUSH(r2);
      if (d1 < MISS) STACK_PUSH(r1);
      if (d0 < MISS) {
        node = r0;
      } else {
        STACK_POP(node);
      }
#else
      stack[stackSize] = r3;
      stackSize += d3 < MISS ? 1u : 0u;
      stack[stackSize] = r2;
      stackSize += d2 < MISS ? 1u : 0u;
      stack[stackSize] = r1;
      stackSize += d1 < MISS ? 1u : 0u;
      bool pop = d0 >= MISS && stackSize > 0u;
      uint top = stack[max(stackSize, 1u) - 1u];
      node = d0 < MISS ? r0 : (pop ? top : DONE);
      stackSize -= pop ? 1u : 0u;
#endif
    }
    if (node == DONE) break;
    uint first = (node & ~LEAF) >> 3u, count = node & 7u;
    for (uint i = first; i < first + count; ++i) {
      vec3 v0 = triangleRow(i, 0u).xyz, e1 = triangleRow(i, 1u).xyz, e2 = triangleRow(i, 2u).xyz;
      vec3 p = cross(direction, e2);
      float inverseDet = 1.0 / dot(e1, p);
      vec3 toOrigin = origin - v0;
      float u = dot(toOrigin, p) * inverseDet;
      vec3 q = cross(toOrigin, e1);
      float v = dot(direction, q) * inverseDet;
      float t = dot(e2, q) * inverseDet;
      if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < tMax) tMax = t;
    }
    STACK_POP(node);
  }
  return tMax < 1e30 ? tMax : -1.0;
}
#else
float closestHit(vec3 origin, vec3 direction) {
  vec3 invDir = 1.0 / direction;
  vec3 originTimesInv = origin * invDir;
  float tMax = 1e30;
  STACK_DECLARE;
  uint node = 0u;
  while (node != DONE) {
    while (node < LEAF) {
#if defined(PLAIN_BINARY_HALF) && defined(PLAIN_STORAGE_BUFFERS)
      uvec4 low = floatBitsToUint(nodes[node * 2u]);
      uvec4 high = floatBitsToUint(nodes[node * 2u + 1u]);
#elif defined(PLAIN_BINARY_HALF)
      uvec4 low = texelFetch(halfNodeTexels, int(node * 2u));
      uvec4 high = texelFetch(halfNodeTexels, int(node * 2u + 1u));
#endif
#ifdef PLAIN_BINARY_HALF
      vec2 aMinXY = unpackHalf2x16(low.z), aMinZMaxX = unpackHalf2x16(low.w);
      vec2 aMaxYZ = unpackHalf2x16(high.x), bMinXY = unpackHalf2x16(high.y);
      vec2 bMinZMaxX = unpackHalf2x16(high.z), bMaxYZ = unpackHalf2x16(high.w);
      vec2 a = slabs(vec2(aMinXY.x, aMinZMaxX.y), vec2(aMinXY.y, aMaxYZ.x),
                     vec2(aMinZMaxX.x, aMaxYZ.y), invDir, originTimesInv, tMax);
      vec2 b = slabs(vec2(bMinXY.x, bMinZMaxX.y), vec2(bMinXY.y, bMaxYZ.x),
                     vec2(bMinZMaxX.x, bMaxYZ.y), invDir, originTimesInv, tMax);
      uint childA = low.x, childB = low.y;
#else
      vec4 n0 = nodeRow(node, 0u), n1 = nodeRow(node, 1u);
      vec4 n2 = nodeRow(node, 2u), n3 = nodeRow(node, 3u);
      vec2 a = slabs(n0.xy, n0.zw, n2.xy, invDir, originTimesInv, tMax);
      vec2 b = slabs(n1.xy, n1.zw, n2.zw, invDir, originTimesInv, tMax);
      uint childA = floatBitsToUint(n3.x), childB = floatBitsToUint(n3.y);
#endif
      bool hitA = a.x <= a.y, hitB = b.x <= b.y;
      if (!hitA && !hitB) {
        STACK_POP(node);
      } else {
        bool aFirst = !hitB || (hitA && a.x <= b.x);
        node = aFirst ? childA : childB;
        if (hitA && hitB) STACK_PUSH(aFirst ? childB : childA);
      }
    }
    if (node == DONE) break;
    uint first = (node & ~LEAF) >> 3u, count = node & 7u;
    for (uint i = first; i < first + count; ++i) {
      vec3 v0 = triangleRow(i, 0u).xyz, e1 = triangleRow(i, 1u).xyz, e2 = triangleRow(i, 2u).xyz;
      vec3 p = cross(direction, e2);
      float inverseDet = 1.0 / dot(e1, p);
      vec3 toOrigin = origin - v0;
      float u = dot(toOrigin, p) * inverseDet;
      vec3 q = cross(toOrigin, e1);
      float v = dot(direction, q) * inverseDet;
      float t = dot(e2, q) * inverseDet;
      if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < tMax) tMax = t;
    }
    STACK_POP(node);
  }
  return tMax < 1e30 ? tMax : -1.0;
}
#endif

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  // A fixed jitter per sample (R2 sequence): every sample a new set of rays.
  vec2 jitter = fract(0.5 + float(params.sampleIndex) * vec2(0.7548777, 0.5698403));
  vec2 ndc = (vec2(pixel) + jitter) / float(params.width) * 2.0 - 1.0;
  vec3 direction = normalize(vec3(ndc.x * params.tanHalfFovY, -ndc.y * params.tanHalfFovY, -1.0));
  distances[pixel.y * params.width + pixel.x] = closestHit(params.position.xyz, direction);
}
