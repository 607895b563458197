// Where a hit is, and where rays leaving it start.
#ifndef RT_GEOMETRY_GLSL
#define RT_GEOMETRY_GLSL

#include "gpu_types.h"
#include "math.glsl"
#include "bindings.glsl"
#include "traverse.glsl"


// Bound on the error of each coordinate of a rebuilt hit position, and with
// margin on the error the intersection routines make when a ray starts that
// close to the surface: 2^-20 of the largest coordinate the primitive is
// built from (8 to 16 float ulps of it). tests/robustness/
// test_reintersection.cpp sees no re-hit down to 2^-23, and rays into small
// spheres far from the origin (1000 radii) bend measurably from 2^-19 up.
// Relative, so the renders of a scene and of the same scene scaled by a
// power of two are identical bit for bit.
const float RT_RELATIVE_POSITION_ERROR = 1.0 / 1048576.0;  // 2^-20

// The hit position (xyz) and the bound on its error (w). The position is
// rebuilt from the primitive rather than taken as origin + t * direction,
// whose error grows with the ray's length and the error of t: spheres
// project onto the surface, triangles interpolate their vertices, cylinders
// move onto the side or cap plane they were hit on. The error left depends
// only on the primitive's coordinates, not on the ray.
vec4 hitPoint(Ray ray, SurfaceHit hit) {
  vec3 p = ray.origin + hit.t * ray.direction;
  float magnitude = maxComponent(abs(p));
  uint kind = primitiveInfo(hit.primitiveIndex).x;
  vec4 a = primitiveRow(hit.primitiveIndex, 0u);
#ifdef RT_FEATURE_SPHERES
  if (kind == RT_PRIM_SPHERE) {
    p = a.xyz + a.w * hit.normal;
    magnitude = maxComponent(abs(a.xyz)) + a.w;
  }
#endif
#ifdef RT_FEATURE_TRIANGLES
  if (kind == RT_PRIM_TRIANGLE) {
    vec3 v1 = primitiveRow(hit.primitiveIndex, 1u).xyz;
    vec3 v2 = primitiveRow(hit.primitiveIndex, 2u).xyz;
    vec3 weights = cornerWeights(hit.barycentric);
    p = weights.x * a.xyz + weights.y * v1 + weights.z * v2;
    magnitude = maxComponent(max(abs(a.xyz), max(abs(v1), abs(v2))));
  }
#endif
#ifdef RT_FEATURE_CYLINDERS
  if (kind == RT_PRIM_CYLINDER) {
    // The side and the caps are each {x : dot(x - center, n) = distance}
    // locally: radius from the axis on the side, half height on a cap.
    vec4 b = primitiveRow(hit.primitiveIndex, 1u);
    bool onCap = abs(dot(hit.normal, b.xyz)) > 0.5;
    float distance = onCap ? b.w : a.w;
    p += (distance - dot(p - a.xyz, hit.normal)) * hit.normal;
    magnitude = maxComponent(abs(a.xyz)) + b.w + a.w;
  }
#endif
  return vec4(p, RT_RELATIVE_POSITION_ERROR * magnitude);
}

// The next float after x towards the sign of `towards` (x itself if 0).
float nextFloatTowards(float x, float towards) {
  if (towards == 0.0) return x;
  if (x == 0.0) return towards > 0.0 ? 1.17549435e-38 : -1.17549435e-38;
  bool awayFromZero = (x > 0.0) == (towards > 0.0);
  return intBitsToFloat(floatBitsToInt(x) + (awayFromZero ? 1 : -1));
}

// Moves p off the surface along n past the error of its coordinates (pbrt's
// OffsetRayOrigin): error e in each coordinate is at most dot(|n|, e) along n.
// Each coordinate then steps one float further, so that rounding p + offset
// cannot bring the point back inside the error bound.
vec3 offsetRayOrigin(vec3 p, float positionError, vec3 n) {
  vec3 offset = positionError * dot(abs(n), vec3(1.0)) * n;
  vec3 moved = p + offset;
  return vec3(nextFloatTowards(moved.x, offset.x), nextFloatTowards(moved.y, offset.y),
              nextFloatTowards(moved.z, offset.z));
}

// A ray leaving the surface at p (with the error bound of hitPoint) towards
// `direction`, started on the side of the surface
// that `direction` points to.
Ray spawnRay(vec3 p, float positionError, vec3 outwardNormal, vec3 direction) {
  vec3 side = dot(direction, outwardNormal) >= 0.0 ? outwardNormal : -outwardNormal;
  return Ray(offsetRayOrigin(p, positionError, side), direction);
}

// Orthonormal tangents of a unit vector (Duff et al. 2017, no branches on
// the axis, continuous except at n.z = -0).
void tangentFrame(vec3 n, out vec3 tangent, out vec3 bitangent) {
  float sign = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sign + n.z);
  float b = n.x * n.y * a;
  tangent = vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  bitangent = vec3(b, sign + n.y * n.y * a, -n.y);
}

// A finite value, or 0 for NaN and +-Inf. Tested on the bit pattern because
// a driver may fold isnan()/isinf() away.
float finiteOrZero(float x) {
  return (floatBitsToUint(x) & 0x7f800000u) == 0x7f800000u ? 0.0 : x;
}

vec3 finiteOrZero(vec3 v) { return vec3(finiteOrZero(v.x), finiteOrZero(v.y), finiteOrZero(v.z)); }

#endif
