// Primary rays: pinhole, or a thin lens focused at sceneInfo.focusDistance.
#ifndef RT_CAMERA_GLSL
#define RT_CAMERA_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "intersect.glsl"

// Uniform point on the unit disc (concentric mapping: keeps strata compact).
vec2 concentricDisc(vec2 u) {
  vec2 offset = 2.0 * u - 1.0;
  if (offset.x == 0.0 && offset.y == 0.0) return vec2(0.0);
  const float quarterPi = 0.78539816;
  float r;
  float theta;
  if (abs(offset.x) > abs(offset.y)) {
    r = offset.x;
    theta = quarterPi * (offset.y / offset.x);
  } else {
    r = offset.y;
    theta = 2.0 * quarterPi - quarterPi * (offset.x / offset.y);
  }
  return r * vec2(cos(theta), sin(theta));
}

// `filmPoint` is in pixels from the image's top-left corner.
Ray cameraRay(vec2 filmPoint, vec2 lensSample) {
  vec2 ndc = 2.0 * filmPoint / vec2(sceneInfo.width, sceneInfo.height) - 1.0;
  vec2 screen = vec2(ndc.x * sceneInfo.aspect, -ndc.y) * sceneInfo.tanHalfFovY;
  vec3 direction = normalize(sceneInfo.cameraForward + screen.x * sceneInfo.cameraRight +
                             screen.y * sceneInfo.cameraUp);
  Ray ray = Ray(sceneInfo.cameraPosition, direction);
#ifdef RT_FEATURE_THIN_LENS
  if (sceneInfo.apertureRadius > 0.0) {
    // Every ray through the lens meets the pinhole ray on the focal plane.
    float alongAxis = dot(direction, sceneInfo.cameraForward);
    vec3 focusPoint = ray.origin + direction * (sceneInfo.focusDistance / alongAxis);
    vec2 lens = sceneInfo.apertureRadius * concentricDisc(lensSample);
    ray.origin += lens.x * sceneInfo.cameraRight + lens.y * sceneInfo.cameraUp;
    ray.direction = normalize(focusPoint - ray.origin);
  }
#endif
  return ray;
}

#endif
