// Points on area lights (GpuAreaLight, GpuEmitter in gpu_types.h), for
// direct lighting by next-event estimation. Needs camera.glsl
// (concentricDisc) and geometry.glsl.
#ifndef RT_LIGHTS_GLSL
#define RT_LIGHTS_GLSL

#include "gpu_types.h"
#include "camera.glsl"
#include "geometry.glsl"
#include "surface.glsl"

#ifdef RT_FEATURE_AREA_LIGHTS
// Rows of uints (bindings.glsl), read per light sample.
RT_UINT_ROWS(RT_BINDING_AREA_LIGHTS, areaLightTexels)
RT_UINT_ROWS(RT_BINDING_EMITTERS, emitterTexels)

// Texel `row` (0..2) of area light `index` (see GpuAreaLight).
uvec4 areaLightRow(uint index, uint row) {
  return RT_ROW(areaLightTexels, index * RT_TEXELS_PER_AREA_LIGHT + row);
}

GpuAreaLight loadAreaLight(uint index) {
  uvec4 diffuse = areaLightRow(index, 0u);
  uvec4 specular = areaLightRow(index, 1u);
  uvec4 rest = areaLightRow(index, 2u);
  return GpuAreaLight(uintBitsToFloat(diffuse.xyz), diffuse.w, uintBitsToFloat(specular.xyz),
                      specular.w, uintBitsToFloat(rest.x), rest.y, rest.z, rest.w);
}

// Texel `row` (0..3) of emitter `index` (see GpuEmitter): a, b, c, then
// kind/cdfEnd/area.
uvec4 emitterRow(uint index, uint row) {
  return RT_ROW(emitterTexels, index * RT_TEXELS_PER_EMITTER + row);
}

float emitterCdfEnd(uint index) { return uintBitsToFloat(emitterRow(index, 3u).y); }

GpuEmitter loadEmitter(uint index) {
  uvec4 info = emitterRow(index, 3u);
  return GpuEmitter(uintBitsToFloat(emitterRow(index, 0u)), uintBitsToFloat(emitterRow(index, 1u)),
                    uintBitsToFloat(emitterRow(index, 2u)), info.x, uintBitsToFloat(info.y),
                    uintBitsToFloat(info.z), info.w);
}

// A point on a light seen from a shading point, standing for a point light
// whose share of the light's intensity is `weight` times that of a point
// light at distance `falloffDistance` (the scene's falloff applies there).
struct LightPoint {
  vec3 position;
  float positionError;  // as hitPoint's bound
  vec3 normal;          // unit; its side does not matter (lights emit both ways)
  float falloffDistance;
  float weight;
};

// The piece of `light` whose share of the area holds u.x, found by binary
// search over the cumulative shares; u.x is rescaled to [0, 1) inside the
// piece, so stratification carries over to the point on it.
uint pickEmitter(GpuAreaLight light, inout vec2 u) {
  uint low = light.firstEmitter;
  uint high = light.firstEmitter + light.emitterCount - 1u;
  while (low < high) {
    uint middle = (low + high) / 2u;
    if (u.x < emitterCdfEnd(middle)) {
      high = middle;
    } else {
      low = middle + 1u;
    }
  }
  float start = low == light.firstEmitter ? 0.0 : emitterCdfEnd(low - 1u);
  float width = emitterCdfEnd(low) - start;
  u.x = width > 0.0 ? clamp((u.x - start) / width, 0.0, 0.99999994) : 0.0;
  return low;
}

LightPoint pointOnTriangle(GpuEmitter piece, vec2 u) {
  // Uniform by area: the square root warps the unit square onto the triangle.
  float root = sqrt(u.x);
  vec3 weights = vec3(1.0 - root, root * (1.0 - u.y), root * u.y);
  vec3 v0 = piece.a.xyz;
  vec3 v1 = piece.b.xyz;
  vec3 v2 = piece.c.xyz;
  vec3 p = weights.x * v0 + weights.y * v1 + weights.z * v2;
  float magnitude = maxComponent(max(abs(v0), max(abs(v1), abs(v2))));
  return LightPoint(p, RT_RELATIVE_POSITION_ERROR * magnitude,
                    normalize(cross(v1 - v0, v2 - v0)), -1.0, 1.0);
}

LightPoint pointOnSphereByArea(vec3 center, float radius, vec2 u) {
  float z = 1.0 - 2.0 * u.x;
  float r = sqrt(max(0.0, 1.0 - z * z));
  float phi = 2.0 * RT_PI * u.y;
  vec3 n = vec3(r * cos(phi), r * sin(phi), z);
  float magnitude = maxComponent(abs(center)) + radius;
  return LightPoint(center + radius * n, RT_RELATIVE_POSITION_ERROR * magnitude, n, -1.0, 1.0);
}

// Uniform over the cone of directions in which the sphere is seen from p
// (pbrt's sphere sampling): no sample is wasted on the far side. A lamp
// sphere of radiance L lights p with L cos per unit solid angle; the host
// sets L so that, facing it, p gets exactly what a point light of the same
// intensity at the centre gives: the solid angle of the cone relative to
// that of the disc pi R^2 / d^2 is the weight. From inside the sphere every
// direction sees it: uniform by area.
LightPoint pointOnSphere(vec3 center, float radius, vec3 p, vec2 u) {
  vec3 toCenter = center - p;
  float distance2 = dot(toCenter, toCenter);
  if (distance2 <= radius * radius * 1.0001) return pointOnSphereByArea(center, radius, u);
  float distance = sqrt(distance2);
  float sin2Max = radius * radius / distance2;
  // 1 - cos(theta_max) without cancellation for small or distant spheres.
  float oneMinusCosMax = sin2Max / (1.0 + sqrt(1.0 - sin2Max));
  float oneMinusCos = u.x * oneMinusCosMax;
  float cosTheta = 1.0 - oneMinusCos;
  float sin2Theta = oneMinusCos * (2.0 - oneMinusCos);
  float sinTheta = sqrt(max(0.0, sin2Theta));
  float phi = 2.0 * RT_PI * u.y;
  vec3 axis = toCenter / distance;
  vec3 tangent;
  vec3 bitangent;
  tangentFrame(axis, tangent, bitangent);
  vec3 direction = sinTheta * cos(phi) * tangent + sinTheta * sin(phi) * bitangent +
                   cosTheta * axis;
  // Nearest intersection along the direction, then onto the surface exactly.
  float along = distance * cosTheta - sqrt(max(0.0, radius * radius - distance2 * sin2Theta));
  vec3 n = normalize(p + along * direction - center);
  float magnitude = maxComponent(abs(center)) + radius;
  float coneOverDisc = 2.0 * oneMinusCosMax / sin2Max;  // 2 / (1 + cos theta_max)
  return LightPoint(center + radius * n, RT_RELATIVE_POSITION_ERROR * magnitude, n, distance,
                    coneOverDisc);
}

// Uniform by area over the side and both caps.
LightPoint pointOnCylinder(GpuEmitter piece, vec2 u) {
  vec3 center = piece.a.xyz;
  float radius = piece.a.w;
  vec3 axis = piece.b.xyz;
  float halfHeight = piece.b.w;
  vec3 tangent;
  vec3 bitangent;
  tangentFrame(axis, tangent, bitangent);
  float side = 2.0 * halfHeight;
  float sideShare = side / (side + radius);  // side 2 pi r 2h against caps 2 pi r^2
  float magnitude = maxComponent(abs(center)) + halfHeight + radius;
  float error = RT_RELATIVE_POSITION_ERROR * magnitude;
  if (u.x < sideShare) {
    float phi = 2.0 * RT_PI * (u.x / sideShare);
    vec3 n = cos(phi) * tangent + sin(phi) * bitangent;
    return LightPoint(center + (2.0 * u.y - 1.0) * halfHeight * axis + radius * n, error, n, -1.0,
                      1.0);
  }
  float capU = (u.x - sideShare) / (1.0 - sideShare);
  float capSign = capU < 0.5 ? -1.0 : 1.0;
  vec2 disc = radius * concentricDisc(vec2(fract(2.0 * capU), u.y));
  vec3 p = center + capSign * halfHeight * axis + disc.x * tangent + disc.y * bitangent;
  return LightPoint(p, error, capSign * axis, -1.0, 1.0);
}

// Which kinds of emitter pieces the scene has (bits 1 << RT_PRIM_*, set by
// the host): the others' code is not built, since CPU drivers run every
// branch for all lanes.
#ifndef RT_EMITTER_KINDS
#define RT_EMITTER_KINDS ((1u << RT_PRIM_SPHERE) | (1u << RT_PRIM_TRIANGLE) | (1u << RT_PRIM_CYLINDER))
#endif

bool emitterKindBuilt(uint kind) { return (RT_EMITTER_KINDS & (1u << kind)) != 0u; }

// A point on `light` for shading point p; u is the sample's 2D point.
// falloffDistance < 0 means: the distance to the point itself.
LightPoint samplePointOnLight(GpuAreaLight light, vec3 p, vec2 u) {
  GpuEmitter piece = loadEmitter(pickEmitter(light, u));
  bool sphere = emitterKindBuilt(RT_PRIM_SPHERE) && piece.kind == RT_PRIM_SPHERE;
  bool cylinder = emitterKindBuilt(RT_PRIM_CYLINDER) && piece.kind == RT_PRIM_CYLINDER;
  if (sphere && light.emitterCount == 1u) return pointOnSphere(piece.a.xyz, piece.a.w, p, u);
  LightPoint point = LightPoint(piece.a.xyz, 0.0, vec3(0.0, 0.0, 1.0), -1.0, 0.0);
  if (sphere) point = pointOnSphereByArea(piece.a.xyz, piece.a.w, u);
  if (cylinder) point = pointOnCylinder(piece, u);
  if (emitterKindBuilt(RT_PRIM_TRIANGLE) && !sphere && !cylinder) {
    point = pointOnTriangle(piece, u);
  }
  // A Lambertian light of the same power sends 2 |cos| as much as the
  // isotropic one towards a direction at angle acos(cos) to its normal.
  if (light.profile == RT_EMISSION_LAMBERTIAN) {
    point.weight = 2.0 * abs(dot(point.normal, normalize(point.position - p)));
  }
  return point;
}
#endif

#endif
