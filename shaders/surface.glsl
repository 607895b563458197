// What shading needs at a hit: position, normals, texture coordinates.
#ifndef RT_SURFACE_GLSL
#define RT_SURFACE_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "traverse.glsl"
#include "geometry.glsl"

#ifdef RT_FEATURE_VERTICES
RT_FLOAT_ROWS(RT_BINDING_VERTICES, vertexTexels)

// Texel `row` (0..1) of vertex `index` (see GpuVertex): normal/u, then colour/v.
vec4 vertexRow(uint index, uint row) {
  return RT_ROW(vertexTexels, index * RT_TEXELS_PER_VERTEX + row);
}

GpuVertex loadVertex(uint index) {
  vec4 normalU = vertexRow(index, 0u);
  vec4 colorV = vertexRow(index, 1u);
  return GpuVertex(normalU.xyz, normalU.w, colorV.xyz, colorV.w);
}
#endif

struct SurfacePoint {
  vec3 position;
  float positionError;   // bound on the error of each coordinate of position
  vec3 geometricNormal;  // outward (winding) normal of the surface
  vec3 shadingNormal;    // interpolated normal, on the geometric normal's side
  vec2 uv;
#ifdef RT_FEATURE_VERTEX_COLORS
  vec3 vertexColor;  // interpolated; the diffuse colour is multiplied by it
#endif
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
// UVs and, if `smoothNormals`, the shading normal from the corners' vertex records.
// `normalMatrix` takes vertex normals to world space.
void interpolateVertices(uvec3 indices, bool smoothNormals, mat3 normalMatrix, vec2 barycentric,
                         inout SurfacePoint surface) {
  GpuVertex v0 = loadVertex(indices.x);
  GpuVertex v1 = loadVertex(indices.y);
  GpuVertex v2 = loadVertex(indices.z);
  vec3 weights = vec3(1.0 - barycentric.x - barycentric.y, barycentric);
  surface.uv = weights.x * vec2(v0.u, v0.v) + weights.y * vec2(v1.u, v1.v) +
               weights.z * vec2(v2.u, v2.v);
#ifdef RT_FEATURE_VERTEX_COLORS
  surface.vertexColor = weights.x * v0.color + weights.y * v1.color + weights.z * v2.color;
#endif
  if (!smoothNormals) return;
  vec3 interpolated = normalMatrix * (weights.x * v0.normal + weights.y * v1.normal +
                                    weights.z * v2.normal);
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
#ifdef RT_FEATURE_VERTEX_COLORS
  surface.vertexColor = vec3(1.0);
#endif
  GpuPrimitive prim = loadPrimitive(hit.primitiveIndex);
#ifdef RT_FEATURE_SPHERES
  if (prim.kind == RT_PRIM_SPHERE) surface.uv = sphereUv(hit.normal);
#endif
#ifdef RT_FEATURE_CYLINDERS
  if (prim.kind == RT_PRIM_CYLINDER) surface.uv = cylinderUv(surface.position, prim.a, prim.b);
#endif
#ifdef RT_FEATURE_VERTICES
  bool smoothNormals = (prim.flags & RT_PRIM_SMOOTH) != 0u;
  if (prim.kind == RT_PRIM_TRIANGLE && (prim.flags & RT_PRIM_HAS_VERTICES) != 0u) {
    uvec3 corners = floatBitsToUint(vec3(prim.a.w, prim.b.w, prim.c.w));
    interpolateVertices(corners, smoothNormals, mat3(1.0), hit.barycentric, surface);
  }
#ifdef RT_FEATURE_MESHES
  if (prim.kind == RT_PRIM_INSTANCE && (prim.flags & RT_PRIM_HAS_VERTICES) != 0u) {
    uvec3 corners = floatBitsToUint(vec3(itemRow(hit.triangleIndex, 0u).w,
                                         itemRow(hit.triangleIndex, 1u).w,
                                         itemRow(hit.triangleIndex, 2u).w));
    // Columns a, b, c: the transpose of world-to-object, the normal matrix.
    mat3 normalMatrix = mat3(prim.a.xyz, prim.b.xyz, prim.c.xyz);
    interpolateVertices(corners, smoothNormals, normalMatrix, hit.barycentric, surface);
  }
#endif
#endif
  return surface;
}

#endif
