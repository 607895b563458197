// Scene queries over the flattened BVH: closest hit and any hit (shadows).
#ifndef RT_TRAVERSE_GLSL
#define RT_TRAVERSE_GLSL

// "No hit" distance: the largest round float, finite because a driver may
// assume no infinities in arithmetic (fast-math).
const float RT_FAR = 3.0e38;

struct SurfaceHit {
  float t;
  uint primitiveIndex;
  vec3 normal;       // outward geometric normal
  vec2 barycentric;  // triangles: weights of v1 and v2
};

// Reciprocal direction with zero components replaced by a tiny signed value,
// so the slab test never computes 0 * inf = NaN.
vec3 safeReciprocal(vec3 d) {
  const float tiny = 1e-30;
  vec3 magnitude = max(abs(d), vec3(tiny));
  return vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0) / magnitude;
}

// Entry distance of the ray into the box, or +inf when it misses (tMin, tMax).
float boxEntry(vec3 boundsMin, vec3 boundsMax, Ray ray, vec3 invDir, float tMin, float tMax) {
  vec3 t0 = (boundsMin - ray.origin) * invDir;
  vec3 t1 = (boundsMax - ray.origin) * invDir;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, tMin));
  float exit = min(min(far.x, far.y), min(far.z, tMax));
  // Widen by a few ulps: the float slab test may otherwise miss a primitive
  // lying exactly on the box face (robust traversal, as in pbrt-v4).
  return enter <= exit * 1.0000004 ? enter : RT_FAR;
}

#ifdef RT_COUNT_RAYS
uint raysTraced = 0u;  // rays this invocation traced, for benchmarks
#endif

// Walks the BVH; with anyHit it stops at the first intersection found.
bool traverse(Ray ray, float tMin, inout float tMax, bool anyHit, out SurfaceHit hit) {
  hit.t = -1.0;
  hit.primitiveIndex = 0u;
  hit.normal = vec3(0.0, 0.0, 1.0);
  hit.barycentric = vec2(0.0);
#ifdef RT_COUNT_RAYS
  ++raysTraced;
#endif
  if (sceneInfo.bvhNodeCount == 0u) return false;
  vec3 invDir = safeReciprocal(ray.direction);
  uint stack[RT_BVH_MAX_DEPTH];
  uint stackSize = 0u;
  uint node = 0u;
  GpuBvhNode root = loadNode(0u);
  if (boxEntry(root.boundsMin, root.boundsMax, ray, invDir, tMin, tMax) ==
      RT_FAR) {
    return false;
  }
  while (true) {
    GpuBvhNode current = loadNode(node);
    if (current.count > 0u) {
      for (uint i = current.firstIndex; i < current.firstIndex + current.count; ++i) {
        vec3 normal;
        vec2 barycentric;
        if (intersectPrimitive(i, ray, tMin, tMax, normal, barycentric)) {
          hit.t = tMax;
          hit.primitiveIndex = i;
          hit.normal = normal;
          hit.barycentric = barycentric;
          if (anyHit) return true;
        }
      }
    } else {
      uint left = current.firstIndex;
      uint right = left + 1u;
      GpuBvhNode leftNode = loadNode(left);
      GpuBvhNode rightNode = loadNode(right);
      float tLeft = boxEntry(leftNode.boundsMin, leftNode.boundsMax, ray, invDir,
                             tMin, tMax);
      float tRight = boxEntry(rightNode.boundsMin, rightNode.boundsMax, ray, invDir,
                              tMin, tMax);
      bool hitLeft = tLeft != RT_FAR;
      bool hitRight = tRight != RT_FAR;
      if (hitLeft && hitRight) {
        // Visit the nearer child first; the farther one waits on the stack.
        bool leftFirst = tLeft <= tRight;
        node = leftFirst ? left : right;
        stack[stackSize++] = leftFirst ? right : left;
        continue;
      }
      if (hitLeft || hitRight) {
        node = hitLeft ? left : right;
        continue;
      }
    }
    if (stackSize == 0u) break;
    node = stack[--stackSize];
  }
  return hit.t >= 0.0;
}

bool closestHit(Ray ray, float tMin, float tMax, out SurfaceHit hit) {
  return traverse(ray, tMin, tMax, false, hit);
}

bool occluded(Ray ray, float tMin, float tMax) {
  SurfaceHit ignored;
  return traverse(ray, tMin, tMax, true, ignored);
}

#endif
