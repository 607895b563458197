// Scene queries: closest hit and any hit (shadows), through the renderer's
// own BVH (traverse_bvh.glsl) or, with --accel hardware, the driver's
// acceleration structures (traverse_hardware.glsl).
#ifndef RT_TRAVERSE_GLSL
#define RT_TRAVERSE_GLSL

#ifdef RT_ACCEL_HARDWARE
#include "traverse_hardware.glsl"
#else
#include "traverse_bvh.glsl"
#endif

bool closestHit(Ray ray, float tMin, float tMax, out SurfaceHit hit) {
  return traverse(ray, tMin, tMax, false, hit);
}

bool occluded(Ray ray, float tMin, float tMax) {
  SurfaceHit ignored;
  return traverse(ray, tMin, tMax, true, ignored);
}

#endif
