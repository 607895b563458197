// Where a hit is, and where rays leaving it start.
#ifndef RT_GEOMETRY_GLSL
#define RT_GEOMETRY_GLSL

// Hit position. On spheres the point is projected back onto the surface,
// which removes most of the error of origin + t * direction.
vec3 hitPosition(Ray ray, SurfaceHit hit) {
  vec3 p = ray.origin + hit.t * ray.direction;
#ifdef RT_FEATURE_SPHERES
  if (primitiveInfo(hit.primitiveIndex).x == RT_PRIM_SPHERE) {
    vec4 sphere = primitiveRow(hit.primitiveIndex, 0u);
    p = sphere.xyz + sphere.w * hit.normal;
  }
#endif
  return p;
}

// Moves a ray origin off the surface along the normal by a fixed number of
// float ulps of the position (Waechter and Binder, Ray Tracing Gems ch. 6), so
// the offset scales with the coordinates instead of being a fixed epsilon.
// Near the origin, where ulps become tiny, a small absolute offset is used.
vec3 offsetRayOrigin(vec3 p, vec3 n) {
  const float nearOrigin = 1.0 / 32.0;
  const float absoluteScale = 1.0 / 65536.0;
  const float ulpScale = 256.0;
  ivec3 ulps = ivec3(ulpScale * n);
  ivec3 signedUlps = ivec3(p.x < 0.0 ? -ulps.x : ulps.x, p.y < 0.0 ? -ulps.y : ulps.y,
                           p.z < 0.0 ? -ulps.z : ulps.z);
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + signedUlps);
  return vec3(abs(p.x) < nearOrigin ? p.x + absoluteScale * n.x : moved.x,
              abs(p.y) < nearOrigin ? p.y + absoluteScale * n.y : moved.y,
              abs(p.z) < nearOrigin ? p.z + absoluteScale * n.z : moved.z);
}

// A ray leaving the surface at p towards `direction`, started on the side of
// the surface that `direction` points to.
Ray spawnRay(vec3 p, vec3 outwardNormal, vec3 direction) {
  vec3 side = dot(direction, outwardNormal) >= 0.0 ? outwardNormal : -outwardNormal;
  return Ray(offsetRayOrigin(p, side), direction);
}

// A finite value, or 0 for NaN and +-Inf. Tested on the bit pattern because
// a driver may fold isnan()/isinf() away.
float finiteOrZero(float x) {
  return (floatBitsToUint(x) & 0x7f800000u) == 0x7f800000u ? 0.0 : x;
}

vec3 finiteOrZero(vec3 v) { return vec3(finiteOrZero(v.x), finiteOrZero(v.y), finiteOrZero(v.z)); }

#endif
