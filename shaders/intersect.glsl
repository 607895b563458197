// Ray-primitive intersection. Every routine takes a unit direction and the
// open interval (tMin, tMax); on a hit it returns true, shrinks tMax to the
// hit distance and writes the outward geometric normal (unit).
#ifndef RT_INTERSECT_GLSL
#define RT_INTERSECT_GLSL

#include "gpu_types.h"
#include "bindings.glsl"

struct Ray {
  vec3 origin;
  vec3 direction;  // unit length
};

#ifdef RT_FEATURE_SPHERES
// Distance to the sphere from the chord midpoint instead of the textbook
// discriminant b^2 - c, which cancels catastrophically for small or distant
// spheres (Ray Tracing Gems, ch. 7).
bool intersectSphere(vec3 center, float radius, Ray ray, float tMin, inout float tMax,
                     out vec3 normal) {
  vec3 f = ray.origin - center;
  float b = dot(f, ray.direction);
  vec3 chord = f - b * ray.direction;
  float discriminant = radius * radius - dot(chord, chord);
  if (discriminant < 0.0) return false;
  float c = dot(f, f) - radius * radius;
  float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(discriminant);
  float t0 = c / q;
  float t1 = q;
  if (t0 > t1) {
    float swapped = t0;
    t0 = t1;
    t1 = swapped;
  }
  float t = t0 > tMin ? t0 : t1;
  if (!(t > tMin && t < tMax)) return false;
  tMax = t;
  normal = normalize(ray.origin + t * ray.direction - center);
  return true;
}
#endif

// Watertight ray/triangle test (Woop, Benthin and Wald, JCGT 2013). The
// vertices move into a frame where the ray runs along +z from the origin:
// a permutation putting the direction's largest axis last and a shear. The
// three edge functions are then 2D cross products of transformed vertices,
// and a shared edge of two triangles gives both exactly opposite values, so
// a ray through an edge or a vertex of a closed mesh cannot slip between
// its triangles. Edges with a zero function count as inside (closed).
// `precise` forbids fusing multiply-adds: fusing could round the same
// shared-vertex expression differently in two triangles.
struct ShearedRay {
  uint dominantAxis;  // ray direction's largest component becomes z
  vec3 shear;         // (-dx/dz, -dy/dz, 1/dz) after the permutation
};

vec3 permuteDominantLast(vec3 v, uint axis) {
  return axis == 0u ? v.yzx : (axis == 1u ? v.zxy : v);
}

ShearedRay shearRay(vec3 direction) {
  vec3 magnitude = abs(direction);
  uint axis = magnitude.x > magnitude.y ? (magnitude.x > magnitude.z ? 0u : 2u)
                                        : (magnitude.y > magnitude.z ? 1u : 2u);
  vec3 d = permuteDominantLast(direction, axis);
  return ShearedRay(axis, vec3(-d.x / d.z, -d.y / d.z, 1.0 / d.z));
}

#ifdef RT_FEATURE_TRIANGLES
// The vertex relative to the ray origin in the sheared frame; z unscaled.
vec3 shearVertex(vec3 vertex, vec3 origin, ShearedRay frame) {
  precise vec3 v = permuteDominantLast(vertex - origin, frame.dominantAxis);
  precise float x = v.x + frame.shear.x * v.z;
  precise float y = v.y + frame.shear.y * v.z;
  return vec3(x, y, v.z);
}

float edgeFunction(vec3 from, vec3 to) {
  precise float value = from.x * to.y - from.y * to.x;
  return value;
}

// Two-sided, against a ray frame built once per ray (shearRay): `barycentric`
// is the weights of v1 and v2. The normal is left to the caller.
bool intersectTriangleSheared(vec3 v0, vec3 v1, vec3 v2, vec3 origin, ShearedRay frame,
                              float tMin, inout float tMax, out vec2 barycentric) {
  vec3 a = shearVertex(v0, origin, frame);
  vec3 b = shearVertex(v1, origin, frame);
  vec3 c = shearVertex(v2, origin, frame);
  float u = edgeFunction(b, c);
  float v = edgeFunction(c, a);
  float w = edgeFunction(a, b);
  barycentric = vec2(0.0);
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
  float det = u + v + w;
  if (det == 0.0) return false;  // the ray lies in the triangle's plane
  float scaledT = frame.shear.z * (u * a.z + v * b.z + w * c.z);
  float t = scaledT / det;
  if (!(t > tMin && t < tMax)) return false;
  tMax = t;
  barycentric = vec2(v, w) / det;
  return true;
}

// Two-sided. The normal follows the winding (v0, v1, v2); `barycentric` is
// the weights of v1 and v2.
bool intersectTriangle(vec3 v0, vec3 v1, vec3 v2, Ray ray, float tMin, inout float tMax,
                       out vec3 normal, out vec2 barycentric) {
  normal = normalize(cross(v1 - v0, v2 - v0));
  return intersectTriangleSheared(v0, v1, v2, ray.origin, shearRay(ray.direction), tMin, tMax,
                                  barycentric);
}
#endif

#ifdef RT_FEATURE_CYLINDERS
// Finite cylinder with flat caps at center +- axis * halfHeight.
bool intersectCylinderSide(vec3 center, vec3 axis, float radius, float halfHeight, Ray ray,
                           float tMin, inout float tMax, inout vec3 normal) {
  vec3 f = ray.origin - center;
  vec3 dPerp = ray.direction - dot(ray.direction, axis) * axis;
  vec3 fPerp = f - dot(f, axis) * axis;
  float a = dot(dPerp, dPerp);
  if (a == 0.0) return false;  // ray parallel to the axis never meets the side
  float b = dot(fPerp, dPerp);
  vec3 chord = fPerp - (b / a) * dPerp;
  float discriminant = a * (radius * radius - dot(chord, chord));
  if (discriminant < 0.0) return false;
  float c = dot(fPerp, fPerp) - radius * radius;
  float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(discriminant);
  float roots[2] = float[2](c / q, q / a);
  if (roots[0] > roots[1]) roots = float[2](roots[1], roots[0]);
  bool found = false;
  for (int i = 0; i < 2 && !found; ++i) {
    float t = roots[i];
    if (!(t > tMin && t < tMax)) continue;
    float along = dot(f + t * ray.direction, axis);
    if (abs(along) > halfHeight) continue;
    tMax = t;
    normal = normalize(fPerp + t * dPerp);
    found = true;
  }
  return found;
}

bool intersectCylinderCaps(vec3 center, vec3 axis, float radius, float halfHeight, Ray ray,
                           float tMin, inout float tMax, inout vec3 normal) {
  float denom = dot(ray.direction, axis);
  if (denom == 0.0) return false;
  bool found = false;
  for (int side = -1; side <= 1; side += 2) {
    vec3 capCenter = center + float(side) * halfHeight * axis;
    float t = dot(capCenter - ray.origin, axis) / denom;
    if (!(t > tMin && t < tMax)) continue;
    vec3 offset = ray.origin + t * ray.direction - capCenter;
    if (dot(offset, offset) > radius * radius) continue;
    tMax = t;
    normal = float(side) * axis;
    found = true;
  }
  return found;
}

bool intersectCylinder(vec3 center, vec3 axis, float radius, float halfHeight, Ray ray,
                       float tMin, inout float tMax, out vec3 normal) {
  normal = axis;
  bool side = intersectCylinderSide(center, axis, radius, halfHeight, ray, tMin, tMax, normal);
  bool caps = intersectCylinderCaps(center, axis, radius, halfHeight, ray, tMin, tMax, normal);
  return side || caps;
}
#endif

// Reads only the texels the primitive's kind needs: on CPU drivers memory
// reads at divergent indices cost more than the intersection arithmetic.
// `barycentric` is (u, v) of v1 and v2 on triangles, (0, 0) on other kinds.
bool intersectPrimitive(uint index, Ray ray, float tMin, inout float tMax, out vec3 normal,
                        out vec2 barycentric) {
  normal = vec3(0.0, 0.0, 1.0);
  barycentric = vec2(0.0);
  uint kind = primitiveInfo(index).x;
#ifdef RT_FEATURE_SPHERES
  if (kind == RT_PRIM_SPHERE) {
    vec4 sphere = primitiveRow(index, 0u);
    return intersectSphere(sphere.xyz, sphere.w, ray, tMin, tMax, normal);
  }
#endif
#ifdef RT_FEATURE_TRIANGLES
  if (kind == RT_PRIM_TRIANGLE) {
    return intersectTriangle(primitiveRow(index, 0u).xyz, primitiveRow(index, 1u).xyz,
                             primitiveRow(index, 2u).xyz, ray, tMin, tMax, normal, barycentric);
  }
#endif
#ifdef RT_FEATURE_CYLINDERS
  if (kind == RT_PRIM_CYLINDER) {
    vec4 a = primitiveRow(index, 0u);
    vec4 b = primitiveRow(index, 1u);
    return intersectCylinder(a.xyz, b.xyz, a.w, b.w, ray, tMin, tMax, normal);
  }
#endif
  return false;
}

#endif
