// Binary mode (RT_BINARY_ONLY): a sample is the hit colour where the primary
// ray meets the scene, else the background. The same values as the Whitted
// tracer gives in binary mode, without building its shading code, which a
// CPU driver would run masked for every lane.
#ifndef RT_BINARY_GLSL
#define RT_BINARY_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "traverse.glsl"

vec3 binaryRadiance(Ray primary) {
  SurfaceHit hit;
  return closestHit(primary, 0.0, RT_FAR, hit) ? sceneInfo.binaryHitColor
                                                : sceneInfo.backgroundColor;
}

#endif
