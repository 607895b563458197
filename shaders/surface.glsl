// What shading needs at a hit: position, normals, texture coordinates.
#ifndef RT_SURFACE_GLSL
#define RT_SURFACE_GLSL

#include "gpu_types.h"
#include "bindings.glsl"
#include "traverse.glsl"
#include "geometry.glsl"
#include "math.glsl"
#include "textures.glsl"
#include "vertices.glsl"

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
// A triangle with vertex records: their indices, its corners (columns) in the
// space of the records' normals, and the matrix that takes that space's
// normals to world space.
struct VertexTriangle {
  uvec3 vertices;
  mat3 corners;
  mat3 normalMatrix;
};

#ifdef RT_FEATURE_NORMAL_MAPS
// The normal `n` (unit) bent by a tangent-space normal map at `uv`. The
// tangent frame is the triangle's own: x along the texture's u on the
// surface (edges e1, e2 with texture coordinates d1, d2 apart), y against
// its v (glTF: the map's +y is up in the image, whose rows v counts down),
// both made perpendicular to n. Per triangle, not the vertex tangents
// glTF's MikkTSpace interpolates: the same on flat faces.
vec3 normalMapped(vec3 n, vec3 e1, vec3 e2, vec2 d1, vec2 d2, vec2 uv, GpuMaterial material) {
  float det = d1.x * d2.y - d2.x * d1.y;
  if (det == 0.0) return n;  // no texture direction on this face
  float orientation = det > 0.0 ? 1.0 : -1.0;  // the derivatives without the division
  vec3 alongU = orientation * (e1 * d2.y - e2 * d1.y);
  vec3 alongV = orientation * (e2 * d1.x - e1 * d2.x);
  vec3 tangent = alongU - n * dot(n, alongU);
  if (!(dot(tangent, tangent) > 0.0)) return n;
  tangent = normalize(tangent);
  vec3 bitangent = cross(n, tangent);
  if (dot(bitangent, alongV) > 0.0) bitangent = -bitangent;
  vec3 m = sampleTexture(material.normalTexture, uv) * 2.0 - 1.0;
  vec3 bent = material.normalScale * (m.x * tangent + m.y * bitangent) + m.z * n;
  return dot(bent, bent) > 0.0 ? normalize(bent) : n;
}
#endif

// UVs, vertex colours and the shading normal from the corners' vertex
// records: interpolated where `smoothNormals`, bent by the material's normal
// map where it has one; else the geometric normal stays.
void interpolateVertices(VertexTriangle triangle, bool smoothNormals, GpuMaterial material,
                         vec2 barycentric, inout SurfacePoint surface) {
  GpuVertex v0 = loadVertex(triangle.vertices.x);
  GpuVertex v1 = loadVertex(triangle.vertices.y);
  GpuVertex v2 = loadVertex(triangle.vertices.z);
  vec3 weights = cornerWeights(barycentric);
  surface.uv = weights.x * vec2(v0.u, v0.v) + weights.y * vec2(v1.u, v1.v) +
               weights.z * vec2(v2.u, v2.v);
#ifdef RT_FEATURE_VERTEX_COLORS
  surface.vertexColor = weights.x * v0.color + weights.y * v1.color + weights.z * v2.color;
#endif
  vec3 normal = smoothNormals
                    ? weights.x * v0.normal + weights.y * v1.normal + weights.z * v2.normal
                    : vec3(0.0);
#ifdef RT_FEATURE_NORMAL_MAPS
  if (material.normalTexture >= 0) {
    vec3 e1 = triangle.corners[1] - triangle.corners[0];
    vec3 e2 = triangle.corners[2] - triangle.corners[0];
    vec3 base = smoothNormals ? normal : cross(e1, e2);
    if (dot(base, base) > 0.0) {
      normal = normalMapped(normalize(base), e1, e2, vec2(v1.u, v1.v) - vec2(v0.u, v0.v),
                            vec2(v2.u, v2.v) - vec2(v0.u, v0.v), surface.uv, material);
    }
  }
#endif
  vec3 world = triangle.normalMatrix * normal;
  if (dot(world, world) > 0.0) {
    world = normalize(world);
    // Interpolated normals may face away on silhouettes: keep them on the
    // geometric side, so shadow and reflection rays stay consistent.
    surface.shadingNormal = dot(world, surface.geometricNormal) >= 0.0 ? world : -world;
  }
}
#endif

// `material`: the hit's (its normal map).
SurfacePoint surfaceAt(Ray ray, SurfaceHit hit, GpuMaterial material) {
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
    VertexTriangle triangle =
        VertexTriangle(triangleVertices(prim.a, prim.b, prim.c),
                       mat3(prim.a.xyz, prim.b.xyz, prim.c.xyz), mat3(1.0));
    interpolateVertices(triangle, smoothNormals, material, hit.barycentric, surface);
  }
#ifdef RT_FEATURE_MESHES
  if (prim.kind == RT_PRIM_INSTANCE && (prim.flags & RT_PRIM_HAS_VERTICES) != 0u) {
    vec4 row0 = itemRow(hit.triangleIndex, 0u);
    vec4 row1 = itemRow(hit.triangleIndex, 1u);
    vec4 row2 = itemRow(hit.triangleIndex, 2u);
    // Columns a, b, c: the transpose of world-to-object, the normal matrix.
    mat3 normalMatrix = mat3(prim.a.xyz, prim.b.xyz, prim.c.xyz);
    VertexTriangle triangle = VertexTriangle(triangleVertices(row0, row1, row2),
                                             mat3(row0.xyz, row1.xyz, row2.xyz), normalMatrix);
    interpolateVertices(triangle, smoothNormals, material, hit.barycentric, surface);
  }
#endif
#endif
  return surface;
}

#endif
