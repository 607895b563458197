// What shading needs at a hit: position, normals, texture coordinates.
#ifndef RT_SURFACE_GLSL
#define RT_SURFACE_GLSL

#ifdef RT_FEATURE_VERTICES
layout(std430, set = 0, binding = RT_BINDING_VERTICES) readonly buffer VertexBuffer {
  GpuVertex vertices[];
};
#endif

struct SurfacePoint {
  vec3 position;
  float positionError;   // bound on the error of each coordinate of position
  vec3 geometricNormal;  // outward (winding) normal of the surface
  vec3 shadingNormal;    // interpolated normal, on the geometric normal's side
  vec2 uv;
};

const float RT_PI = 3.14159265358979;

// Longitude/latitude around the world axis sceneInfo.sphereUvPole (the axis
// closest to the camera's up), v = 0 at the upper pole.
vec2 sphereUv(vec3 n) {
  uint pole = sceneInfo.sphereUvPole;
  float up = n[pole];
  float x = n[(pole + 1u) % 3u];
  float y = n[(pole + 2u) % 3u];
  return vec2(0.5 + atan(y, x) / (2.0 * RT_PI), acos(clamp(up, -1.0, 1.0)) / RT_PI);
}

#ifdef RT_FEATURE_CYLINDERS
// Angle around the axis and height along it on the side; the caps map their
// disc onto the unit square.
vec2 cylinderUv(vec3 p, vec4 centerRadius, vec4 axisHalfHeight) {
  vec3 axis = axisHalfHeight.xyz;
  vec3 reference = abs(axis.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 tangent = normalize(cross(axis, reference));
  vec3 bitangent = cross(axis, tangent);
  vec3 offset = p - centerRadius.xyz;
  float along = dot(offset, axis);
  vec2 around = vec2(dot(offset, tangent), dot(offset, bitangent)) / centerRadius.w;
  if (abs(along) >= axisHalfHeight.w * 0.99999 && dot(around, around) < 0.99998) {
    return 0.5 + 0.5 * around;  // on a cap
  }
  return vec2(0.5 + atan(around.y, around.x) / (2.0 * RT_PI),
              0.5 - 0.5 * along / axisHalfHeight.w);
}
#endif

#ifdef RT_FEATURE_VERTICES
void interpolateVertices(GpuPrimitive prim, vec2 barycentric, inout SurfacePoint surface) {
  GpuVertex v0 = vertices[floatBitsToUint(prim.a.w)];
  GpuVertex v1 = vertices[floatBitsToUint(prim.b.w)];
  GpuVertex v2 = vertices[floatBitsToUint(prim.c.w)];
  vec3 weights = vec3(1.0 - barycentric.x - barycentric.y, barycentric);
  surface.uv = weights.x * vec2(v0.u, v0.v) + weights.y * vec2(v1.u, v1.v) +
               weights.z * vec2(v2.u, v2.v);
  if ((prim.flags & RT_PRIM_SMOOTH) == 0u) return;
  vec3 interpolated = weights.x * v0.normal + weights.y * v1.normal + weights.z * v2.normal;
  if (dot(interpolated, interpolated) > 0.0) {
    interpolated = normalize(interpolated);
    // Interpolated normals may face away on silhouettes: keep them on the
    // geometric side, so shadow and reflection rays stay consistent.
    surface.shadingNormal =
        dot(interpolated, surface.geometricNormal) >= 0.0 ? interpolated : -interpolated;
  }
}
#endif

SurfacePoint surfaceAt(Ray ray, SurfaceHit hit) {
  SurfacePoint surface;
  vec4 point = hitPoint(ray, hit);
  surface.position = point.xyz;
  surface.positionError = point.w;
  surface.geometricNormal = hit.normal;
  surface.shadingNormal = hit.normal;
  surface.uv = hit.barycentric;
  GpuPrimitive prim = loadPrimitive(hit.primitiveIndex);
#ifdef RT_FEATURE_SPHERES
  if (prim.kind == RT_PRIM_SPHERE) surface.uv = sphereUv(hit.normal);
#endif
#ifdef RT_FEATURE_CYLINDERS
  if (prim.kind == RT_PRIM_CYLINDER) surface.uv = cylinderUv(surface.position, prim.a, prim.b);
#endif
#ifdef RT_FEATURE_VERTICES
  if (prim.kind == RT_PRIM_TRIANGLE && (prim.flags & RT_PRIM_HAS_VERTICES) != 0u) {
    interpolateVertices(prim, hit.barycentric, surface);
  }
#endif
  return surface;
}

#endif
