// Blinn-Phong direct lighting from point and area lights, with shadow rays.
#ifndef RT_SHADING_GLSL
#define RT_SHADING_GLSL

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

float lightAttenuation(float distance) {
  float attenuation = sceneInfo.lightScale;
  if (sceneInfo.lightFalloff == RT_FALLOFF_INVERSE_SQUARE) {
    attenuation /= max(distance * distance, 1e-30);
  }
  return attenuation;
}

#ifdef RT_FEATURE_REFRACTION
// Beyond this many transmissive surfaces a shadow ray counts as blocked.
const int RT_MAX_SHADOW_CROSSINGS = 8;

// Fraction of a light's intensity that reaches distance `tMax` along `ray`
// through transmissive surfaces. Shadow rays go straight (refraction does
// not bend them: caustics need sampled bounces), losing the Fresnel
// reflectance and (1 - transmission) at each crossing; an opaque surface
// blocks all.
float shadowTransmittance(Ray ray, float tMax) {
  float transmittance = 1.0;
  float travelled = 0.0;
  for (int crossing = 0; crossing < RT_MAX_SHADOW_CROSSINGS; ++crossing) {
    SurfaceHit hit;
    if (!closestHit(ray, 0.0, tMax - travelled, hit)) return transmittance;
    GpuMaterial blocker = loadMaterial(hitMaterial(hit));
    float cosine = dot(ray.direction, hit.normal);
    float eta = cosine < 0.0 ? 1.0 / blocker.ior : blocker.ior;
    float cosTransmitted;
    float reflectance = dielectricReflectance(abs(cosine), eta, cosTransmitted);
    transmittance *= blocker.transmission * (1.0 - reflectance);
    if (transmittance < RT_MIN_BRANCH_WEIGHT) return 0.0;
    vec4 point = hitPoint(ray, hit);
    Ray next = spawnRay(point.xyz, point.w, hit.normal, ray.direction);
    travelled += dot(next.origin - ray.origin, ray.direction);
    ray = next;
  }
  return 0.0;
}
#endif

// Share of a light that reaches the end of `shadowRay` at distance tMax.
// `throughGlass`: transmissive surfaces let light through (attenuated)
// instead of blocking it; off where sampled bounces carry that light.
float lightVisibility(Ray shadowRay, float tMax, bool throughGlass) {
#ifdef RT_FEATURE_REFRACTION
  if (throughGlass) return shadowTransmittance(shadowRay, tMax);
#endif
  return occluded(shadowRay, 0.0, tMax) ? 0.0 : 1.0;
}

// Unit-length colour: the coursework's renderer tints by the diffuse colour's
// direction, not its magnitude (white (1,1,1) shows as 0.577).
vec3 courseworkTint(vec3 color) {
  float length2 = dot(color, color);
  return length2 > 0.0 ? color * inversesqrt(length2) : vec3(0.0);
}

// The surface's normals turned towards the viewer (surfaces are two-sided).
void faceViewer(inout SurfacePoint surface, vec3 toViewer) {
  if (dot(toViewer, surface.geometricNormal) < 0.0) {
    surface.geometricNormal = -surface.geometricNormal;
    surface.shadingNormal = -surface.shadingNormal;
  }
}

// What direct lighting needs of the point being shaded.
struct ShadingContext {
  SurfacePoint surface;  // facing the viewer
  vec3 toViewer;
  GpuMaterial material;
  vec3 color;  // diffuse colour at the point (texture or plain)
  bool coursework;
};

// The coursework model's colour: a texture's as it is, a plain colour normalised.
vec3 courseworkDiffuseTint(ShadingContext context) {
  return isTextured(context.material) ? context.color : courseworkTint(context.color);
}

// Blinn-Phong light reflected towards the viewer from a light in direction l
// (unit) with diffuse and specular intensities arriving at the point, or 0
// when the light is behind the surface.
vec3 blinnPhong(ShadingContext context, vec3 l, vec3 diffuseIntensity, vec3 specularIntensity) {
  vec3 normal = context.surface.shadingNormal;
  float cosine = dot(normal, l);
  // Light behind the surface as seen from the viewer (by either normal).
  if (cosine <= 0.0 || dot(context.surface.geometricNormal, l) <= 0.0) return vec3(0.0);
  vec3 halfway = normalize(l + context.toViewer);
  // pow(0, 0) is undefined in GLSL (exp2(0 * log2(0)) = NaN on some
  // drivers): exponent 0 is the constant lobe 1.
  float exponent = context.material.specularExponent;
  float highlight = exponent > 0.0 ? pow(max(dot(normal, halfway), 0.0), exponent) : 1.0;
  vec3 diffuse = context.material.kd * diffuseIntensity * cosine;
  vec3 specular = context.material.ks * specularIntensity * highlight;
  if (!context.coursework) {
    diffuse *= context.color;
    specular *= context.material.specularColor;
  }
  return diffuse + specular;
}

vec3 pointLighting(ShadingContext context, bool throughGlass) {
  vec3 p = context.surface.position;
  vec3 radiance = vec3(0.0);
  for (uint i = 0u; i < sceneInfo.pointLightCount; ++i) {
    GpuPointLight light = loadPointLight(i);
    vec3 toLight = light.position - p;
    float distance = length(toLight);
    if (!(distance > 0.0)) continue;
    vec3 l = toLight / distance;
    vec3 reflected = blinnPhong(context, l, light.diffuseIntensity, light.specularIntensity);
    if (maxComponent(reflected) <= 0.0) continue;
    Ray shadowRay = spawnRay(p, context.surface.positionError, context.surface.geometricNormal, l);
    float visibility = lightVisibility(shadowRay, length(light.position - shadowRay.origin),
                                       throughGlass);
    radiance += visibility * lightAttenuation(distance) * reflected;
  }
  return radiance;
}

#ifdef RT_FEATURE_AREA_LIGHTS
// Next-event estimation of one area light: `samples` points on it per pixel
// sample, each lighting like a point light with its share of the intensity.
vec3 areaLighting(ShadingContext context, uint lightIndex, uvec2 pixelSample, uint vertexDepth,
                  bool throughGlass) {
  GpuAreaLight light = loadAreaLight(lightIndex);
  vec3 p = context.surface.position;
  uint dimension = vertexDimension(vertexDepth, RT_VERTEX_DIM_LIGHTS + 2u * lightIndex);
  vec3 radiance = vec3(0.0);
  for (uint sub = 0u; sub < light.samples; ++sub) {
    vec2 u = sampleSubPair(frame.samplerKind, pixelSample.x, pixelSample.y, sub, light.samples,
                           frame.samplesTotal, dimension, frame.seed);
    LightPoint point = samplePointOnLight(light, p, u);
    vec3 toLight = point.position - p;
    float distance = length(toLight);
    if (!(distance > 0.0)) continue;
    vec3 l = toLight / distance;
    vec3 reflected = blinnPhong(context, l, light.diffuseIntensity, light.specularIntensity);
    if (!(maxComponent(reflected) > 0.0)) continue;
    float falloffDistance = point.falloffDistance < 0.0 ? distance : point.falloffDistance;
    reflected *= point.weight * lightAttenuation(falloffDistance);
    // Both ends leave their surfaces by their error bounds, so the ray
    // neither starts inside the shaded surface nor ends inside the light.
    Ray shadowRay = spawnRay(p, context.surface.positionError, context.surface.geometricNormal, l);
    vec3 target = offsetRayOrigin(point.position, point.positionError,
                                  dot(point.normal, l) < 0.0 ? point.normal : -point.normal);
    vec3 toTarget = target - shadowRay.origin;
    float tMax = length(toTarget);
    if (!(tMax > 0.0)) continue;
    shadowRay.direction = toTarget / tMax;
    radiance += lightVisibility(shadowRay, tMax, throughGlass) * reflected;
  }
  return radiance / float(max(light.samples, 1u));
}

// Radiance a ray sees leaving an area light's surface (material.emission
// holds it head on): spheres and Lambertian lights the same from every
// direction; isotropic ones are sheets of points shining in all directions,
// brighter where seen edge on (by the cosine, bounded so that grazing views
// stay finite).
vec3 emittedRadiance(GpuMaterial material, SurfaceHit hit, vec3 direction) {
  if (material.emissionProfile == RT_EMISSION_LAMBERTIAN ||
      primitiveInfo(hit.primitiveIndex).x == RT_PRIM_SPHERE) {
    return material.emission;
  }
  return material.emission / max(abs(dot(direction, hit.normal)), 0.01);
}
#endif

// Light reflected towards the viewer from a surface already facing it, from
// every point and area light. `throughGlass`: shadow rays pass transmissive
// surfaces (see lightVisibility).
vec3 directLighting(ShadingContext context, uvec2 pixelSample, uint vertexDepth,
                    bool throughGlass) {
  vec3 radiance = pointLighting(context, throughGlass);
#ifdef RT_FEATURE_AREA_LIGHTS
  for (uint i = 0u; i < sceneInfo.areaLightCount; ++i) {
    radiance += areaLighting(context, i, pixelSample, vertexDepth, throughGlass);
  }
#endif
  // The coursework model clamps the light reaching the eye first, then tints
  // it (highlights included) by the normalised diffuse colour, or by the
  // texture colour as it is.
  if (!context.coursework) return radiance;
  return courseworkDiffuseTint(context) * min(radiance, vec3(1.0));
}

#endif
