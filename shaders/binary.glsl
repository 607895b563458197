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

#ifdef RT_PRIMARY_PAIRS
// The values of two samples whose primary rays walk together (traversePair):
// rays through one pixel visit nearly the same nodes. Without `hasSecond`
// only the first is traced.
void binaryRadiancePair(Ray first, Ray second, bool hasSecond, out vec3 firstValue,
                        out vec3 secondValue) {
  SurfaceHit firstHit;
  SurfaceHit secondHit;
  traversePair(first, second, bvec2(true, hasSecond), vec2(RT_FAR), false, firstHit, secondHit);
  firstValue = firstHit.t >= 0.0 ? sceneInfo.binaryHitColor : sceneInfo.backgroundColor;
  secondValue = secondHit.t >= 0.0 ? sceneInfo.binaryHitColor : sceneInfo.backgroundColor;
}
#endif

#endif
