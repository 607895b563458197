// Blinn-Phong direct lighting from point and area lights, with shadow rays.
#ifndef RT_SHADING_GLSL
#define RT_SHADING_GLSL

#include "gpu_types.h"
#include "math.glsl"
#include "frame.glsl"
#include "rng.glsl"
#include "traverse.glsl"
#include "geometry.glsl"
#include "surface.glsl"
#include "textures.glsl"
#include "optics.glsl"
#include "lights.glsl"

float lightAttenuation(float distance) {
  float attenuation = sceneInfo.lightScale;
  if (sceneInfo.lightFalloff == RT_FALLOFF_INVERSE_SQUARE) {
    attenuation /= max(distance * distance, 1e-30);
  }
  return attenuation;
}

// Beyond this many transmissive surfaces a shadow ray counts as blocked.
#ifdef RT_FEATURE_REFRACTION
const int RT_MAX_SHADOW_CROSSINGS = 8;
#else
const int RT_MAX_SHADOW_CROSSINGS = 1;
#endif

// The share of a light that a shadow ray lets through: per colour channel
// where glass tints it (RT_MATERIAL_TINTED_TRANSMISSION), else one number.
#ifdef RT_FEATURE_TINTED_TRANSMISSION
#define Transmittance vec3
#else
#define Transmittance float
#endif

// A shadow ray on its way to a light: with `throughGlass`, transmissive
// surfaces let the light through, losing the Fresnel reflectance and
// (1 - transmission) at each crossing, and taking the colour of glass that
// tints (its base colour factor; the texture is not read here). Shadow rays
// go straight: refraction does not bend them, and caustics need sampled
// bounces. Without `throughGlass` (where sampled bounces carry that light)
// an any-hit query decides.
struct ShadowPath {
  Ray ray;                      // from the last crossing on
  float remaining;              // distance from ray.origin to the light
  Transmittance transmittance;  // of the crossings so far
  bool open;                    // not settled yet
};

ShadowPath shadowPath(Ray ray, float tMax) {
  return ShadowPath(ray, tMax, Transmittance(1.0), true);
}

// The path's light once the walks are done: a path still open after the
// most crossings counts as blocked.
Transmittance pathVisibility(ShadowPath path) {
  return path.open ? Transmittance(0.0) : path.transmittance;
}

// Moves an open path past what its last walk found: nothing (the light
// arrives), an opaque surface (blocked), or a crossing through glass.
void crossSurface(inout ShadowPath path, bool found, SurfaceHit hit, bool throughGlass) {
  if (!path.open) return;
  if (!found) {
    path.open = false;
    return;
  }
#ifdef RT_FEATURE_REFRACTION
  if (throughGlass) {
    GpuMaterial blocker = loadMaterial(hitMaterial(hit));
    float cosine = dot(path.ray.direction, hit.normal);
    float eta = interfaceEta(blocker, cosine < 0.0);
    float cosTransmitted;
    float reflectance = dielectricReflectance(abs(cosine), eta, cosTransmitted);
    path.transmittance *= blocker.transmission * (1.0 - reflectance);
#ifdef RT_FEATURE_TINTED_TRANSMISSION
    if ((blocker.flags & RT_MATERIAL_TINTED_TRANSMISSION) != 0u) {
      path.transmittance *= blocker.diffuseColor;
    }
    if (maxComponent(path.transmittance) >= RT_MIN_BRANCH_WEIGHT) {
#else
    if (path.transmittance >= RT_MIN_BRANCH_WEIGHT) {
#endif
      vec4 point = hitPoint(path.ray, hit);
      Ray next = spawnRay(point.xyz, point.w, hit.normal, path.ray.direction);
      path.remaining -= dot(next.origin - path.ray.origin, path.ray.direction);
      path.ray = next;
      return;
    }
  }
#endif
  path.transmittance = Transmittance(0.0);
  path.open = false;
}

bool shadowWalkIsAnyHit(bool throughGlass) {
#ifdef RT_FEATURE_REFRACTION
  return !throughGlass;
#else
  return true;  // nothing to pass through: any hit blocks the light
#endif
}

#ifdef RT_SHADOW_PAIRS
// Share of each light sample's light that reaches the end of its shadow
// ray (length tMax; a negative tMax: not traced, 0), the two rays walked
// together (traversePair). One walk call site for all of it: the walk is
// most of a kernel's code, and every call site is a copy.
void lightVisibilityPair(Ray rayA, float tMaxA, Ray rayB, float tMaxB, bool throughGlass,
                         out Transmittance visibilityA, out Transmittance visibilityB) {
  ShadowPath a = shadowPath(rayA, tMaxA);
  ShadowPath b = shadowPath(rayB, tMaxB);
  a.open = tMaxA >= 0.0;
  b.open = tMaxB >= 0.0;
  bool anyHit = shadowWalkIsAnyHit(throughGlass);
  for (int crossing = 0; crossing < RT_MAX_SHADOW_CROSSINGS && (a.open || b.open); ++crossing) {
    SurfaceHit hitA;
    SurfaceHit hitB;
    traversePair(a.ray, b.ray, bvec2(a.open, b.open), vec2(a.remaining, b.remaining), anyHit,
                 hitA, hitB);
    crossSurface(a, hitA.t >= 0.0, hitA, throughGlass);
    crossSurface(b, hitB.t >= 0.0, hitB, throughGlass);
  }
  visibilityA = pathVisibility(a);
  visibilityB = pathVisibility(b);
}
#else
// Share of a light that reaches the end of `ray` at distance tMax. One walk
// call site for all of it: the walk is most of a kernel's code, and every
// call site is a copy.
Transmittance lightVisibility(Ray ray, float tMax, bool throughGlass) {
  ShadowPath path = shadowPath(ray, tMax);
  bool anyHit = shadowWalkIsAnyHit(throughGlass);
  for (int crossing = 0; crossing < RT_MAX_SHADOW_CROSSINGS && path.open; ++crossing) {
    SurfaceHit hit;
    float limit = path.remaining;
    bool found = traverse(path.ray, 0.0, limit, anyHit, hit);
    crossSurface(path, found, hit, throughGlass);
  }
  return pathVisibility(path);
}
#endif

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

// One shadow-ray sample of a light: what the point receives from it when
// nothing is in the way, and the ray that decides whether something is.
struct LightSample {
  vec3 reflected;  // towards the viewer; 0: nothing to trace
  Ray shadowRay;
  float tMax;
};

LightSample pointLightSample(ShadingContext context, uint index) {
  LightSample lit;
  lit.reflected = vec3(0.0);
  GpuPointLight light = loadPointLight(index);
  vec3 p = context.surface.position;
  vec3 toLight = light.position - p;
  float distance = length(toLight);
  if (!(distance > 0.0)) return lit;
  vec3 l = toLight / distance;
  lit.reflected = blinnPhong(context, l, light.diffuseIntensity, light.specularIntensity) *
                     lightAttenuation(distance);
  lit.shadowRay =
      spawnRay(p, context.surface.positionError, context.surface.geometricNormal, l);
  lit.tMax = length(light.position - lit.shadowRay.origin);
  return lit;
}

// Light splitting (RenderSettings::lightSplit): each hit's area-light
// estimate is made this many times over, each replica with its own shadow
// rays and through the hit's whole shading (clamps included), and the
// replicas are averaged. Where the shading clamps a hit's summed light (the
// coursework model, family B's local light) that average converges to the
// image of one replica, where more samples per light would not. The host
// sets RT_LIGHT_REPLICAS only for scenes with area lights.
#ifdef RT_LIGHT_REPLICAS
const uint RT_REPLICAS = RT_LIGHT_REPLICAS;
#else
const uint RT_REPLICAS = 1u;
#endif

#ifdef RT_FEATURE_AREA_LIGHTS
// Next-event estimation of area light `lightIndex`: sample `sub` of its
// `samples` per pixel sample in replica `replica`, lighting like a point
// light with its share of the intensity. Replica r takes the light's sub-
// samples r * samples.. of RT_REPLICAS * samples, so the replicas stratify
// against each other; each is still the one-replica estimate in expectation.
LightSample areaLightSample(ShadingContext context, GpuAreaLight light, uint lightIndex, uint sub,
                            uint replica, uvec2 pixelSample, uint vertexDepth) {
  LightSample lit;
  lit.reflected = vec3(0.0);
  vec3 p = context.surface.position;
  uint dimension = vertexDimension(vertexDepth, RT_VERTEX_DIM_LIGHTS + 2u * lightIndex);
  vec2 u = sampleSubPair(frame.samplerKind, pixelSample.x, pixelSample.y,
                         replica * light.samples + sub, RT_REPLICAS * light.samples,
                         frame.samplesTotal, dimension, frame.seed);
  LightPoint point = samplePointOnLight(light, p, u);
  vec3 toLight = point.position - p;
  float distance = length(toLight);
  if (!(distance > 0.0)) return lit;
  vec3 l = toLight / distance;
  vec3 reflected = blinnPhong(context, l, light.diffuseIntensity, light.specularIntensity);
  if (!(maxComponent(reflected) > 0.0)) return lit;
  float falloffDistance = point.falloffDistance < 0.0 ? distance : point.falloffDistance;
  // Both ends leave their surfaces by their error bounds, so the ray
  // neither starts inside the shaded surface nor ends inside the light.
  Ray shadowRay = spawnRay(p, context.surface.positionError, context.surface.geometricNormal, l);
  vec3 target = offsetRayOrigin(point.position, point.positionError,
                                dot(point.normal, l) < 0.0 ? point.normal : -point.normal);
  vec3 toTarget = target - shadowRay.origin;
  float tMax = length(toTarget);
  if (!(tMax > 0.0)) return lit;
  shadowRay.direction = toTarget / tMax;
  lit.reflected = reflected * point.weight * lightAttenuation(falloffDistance) /
                     float(max(light.samples, 1u));
  lit.shadowRay = shadowRay;
  lit.tMax = tMax;
  return lit;
}

#endif

#if defined(RT_FEATURE_AREA_LIGHTS) || defined(RT_FEATURE_GLOW)
// Radiance a ray sees leaving an area light's surface (material.emission
// holds it head on): spheres and Lambertian lights the same from every
// direction; isotropic ones are sheets of points shining in all directions,
// brighter where seen edge on (by the cosine, bounded so that grazing views
// stay finite). A glow shows its emission times its texture at the surface
// point, if it has one; an unlit surface's, times its vertex colours too.
vec3 emittedRadiance(GpuMaterial material, SurfaceHit hit, vec3 direction, SurfacePoint surface) {
#ifdef RT_FEATURE_GLOW
  if (isGlowProfile(material.emissionProfile)) {
    vec3 glow = material.emission;
#ifdef RT_FEATURE_TEXTURES
    if (material.emissionTexture >= 0) glow *= sampleTexture(material.emissionTexture, surface.uv);
#endif
#ifdef RT_FEATURE_VERTEX_COLORS
    if (material.emissionProfile == RT_EMISSION_UNLIT) glow *= surface.vertexColor;
#endif
    return glow;
  }
#endif
  if (material.emissionProfile == RT_EMISSION_LAMBERTIAN ||
      primitiveInfo(hit.primitiveIndex).x == RT_PRIM_SPHERE) {
    return material.emission;
  }
  return material.emission / max(abs(dot(direction, hit.normal)), 0.01);
}
#endif

// The light samples of one shading point, in order: every point light,
// then each area light's samples (with light splitting, all of them once
// per replica, replica by replica).
struct LightCursor {
  uint next;  // index of the next sample
#ifdef RT_FEATURE_AREA_LIGHTS
  uint areaLight;  // the area light of the next area sample, and its sample
  uint sub;
  uint replica;
  GpuAreaLight light;
#endif
};

LightCursor firstLight() {
  LightCursor cursor;
  cursor.next = 0u;
#ifdef RT_FEATURE_AREA_LIGHTS
  cursor.areaLight = 0u;
  cursor.sub = 0u;
  cursor.replica = 0u;
  if (sceneInfo.areaLightCount > 0u) cursor.light = loadAreaLight(0u);
#endif
  return cursor;
}

// Light samples of one shading point with `replicas` replicas: the point
// lights', then the area lights' of every replica.
uint lightSampleCount(uint replicas) {
  uint samples = sceneInfo.pointLightCount;
#ifdef RT_FEATURE_AREA_LIGHTS
  samples += replicas * sceneInfo.areaLightSamples;
#endif
  return samples;
}

LightSample nextLightSample(inout LightCursor cursor, ShadingContext context, uvec2 pixelSample,
                            uint vertexDepth) {
  uint k = cursor.next++;
#ifdef RT_FEATURE_AREA_LIGHTS
  if (k >= sceneInfo.pointLightCount) {
    LightSample lit = areaLightSample(context, cursor.light, cursor.areaLight, cursor.sub,
                                      cursor.replica, pixelSample, vertexDepth);
    if (++cursor.sub >= cursor.light.samples) {
      cursor.sub = 0u;
      if (++cursor.areaLight >= sceneInfo.areaLightCount && RT_REPLICAS > 1u) {
        cursor.areaLight = 0u;
        ++cursor.replica;
      }
      if (cursor.areaLight < sceneInfo.areaLightCount) {
        cursor.light = loadAreaLight(cursor.areaLight);
      }
    }
    return lit;
  }
#endif
  return pointLightSample(context, k);
}

// Whether a sample's shadow ray is traced: a sample that could add less
// than `negligible` is counted at half its unshadowed light instead.
bool shadowRayTraced(LightSample lit, float negligible) {
  float worth = maxComponent(lit.reflected);
  return worth > 0.0 && !(worth < negligible);
}

// What a sample adds, given the share of its light that its shadow ray
// found (read only where the ray was traced).
vec3 sampleContribution(LightSample lit, float negligible, Transmittance visibility) {
  float worth = maxComponent(lit.reflected);
  if (!(worth > 0.0)) return vec3(0.0);
  if (worth < negligible) return 0.5 * lit.reflected;
  return visibility * lit.reflected;
}

// The light a hit's summed light samples send the viewer: the coursework
// model clamps the light reaching the eye first, then tints it (highlights
// included) by the normalised diffuse colour, or by the texture colour as it
// is.
vec3 shadedDirect(ShadingContext context, vec3 radiance) {
  if (!context.coursework) return radiance;
  return courseworkDiffuseTint(context) * min(radiance, vec3(1.0));
}

// A hit's own light from its direct light, by the conventions: plus the
// ambient term; for family B clamped to 1 and weighted by what the mirror
// and refraction branches leave (a full mirror shows only its reflection).
vec3 localLight(ShadingContext context, vec3 direct) {
  vec3 local = direct + sceneInfo.ambient * context.color;
  if (sceneInfo.mirrorsReplaceLocalLight == 0u) return local;
  float mirrorWeight = 0.0;
#ifdef RT_FEATURE_REFLECTION
  mirrorWeight += context.material.reflectivity;
#endif
#ifdef RT_FEATURE_REFRACTION
  mirrorWeight += context.material.transmission;
#endif
  return min(local, vec3(1.0)) * max(1.0 - mirrorWeight, 0.0);
}

// A hit's light samples summed as they come in.
struct LightSums {
  vec3 current;  // of the samples so far (with splitting: of this replica)
#ifdef RT_LIGHT_REPLICAS
  vec3 pointLights;  // the point lights' part, which every replica shares
  vec3 replicas;     // the local light of the replicas done
  uint replicaLeft;  // area samples still to come in this replica
#endif
};

LightSums noLightSums() {
#ifdef RT_LIGHT_REPLICAS
  return LightSums(vec3(0.0), vec3(0.0), vec3(0.0), sceneInfo.areaLightSamples);
#else
  return LightSums(vec3(0.0));
#endif
}

// Adds light sample k's contribution. With splitting, a replica ends after
// its area samples: its sum goes through the hit's shading on its own, and
// the next replica starts again from the point lights' part (traced once).
void addLightSample(inout LightSums sums, ShadingContext context, uint k, vec3 contribution) {
  sums.current += contribution;
#ifdef RT_LIGHT_REPLICAS
  if (k + 1u == sceneInfo.pointLightCount) sums.pointLights = sums.current;
  if (k < sceneInfo.pointLightCount || --sums.replicaLeft > 0u) return;
  sums.replicas += localLight(context, shadedDirect(context, sums.current));
  sums.current = sums.pointLights;
  sums.replicaLeft = sceneInfo.areaLightSamples;
#endif
}

// A hit's own light (localLight) from every point light and every sample of
// every area light, in one loop (see lightVisibility). `throughGlass`:
// shadow rays pass transmissive surfaces. `pathWeight` is what the hit's
// light is worth in the pixel: a sample that could add less than the
// bailout's share of it (all samples of the hit together at most the
// bailout) is not traced but counted at half its unshadowed light, in error
// by at most half that share whether it was lit or not; so glass, whose
// highlight is dark nearly everywhere, traces almost no shadow rays (README
// "Speed vs accuracy"). With RT_SHADOW_PAIRS the samples go two by two,
// their shadow rays walked together; the sums are made in the same order,
// so the image is the same.
vec3 hitLocalLight(ShadingContext context, uvec2 pixelSample, uint vertexDepth, bool throughGlass,
                   float pathWeight) {
  LightSums sums = noLightSums();
  uint samples = lightSampleCount(RT_REPLICAS);
  // The share of one replica's samples: each sample's decision is the one
  // it gets without splitting.
  uint replicaSamples = lightSampleCount(1u);
  LightCursor cursor = firstLight();
  // `--bailout 0` (the floor) traces every sample.
  float share =
      sceneInfo.branchBailout / (max(pathWeight, 1e-30) * float(max(replicaSamples, 1u)));
  float negligible = sceneInfo.branchBailout > RT_MIN_BRANCH_WEIGHT ? share : 0.0;
#ifdef RT_SHADOW_PAIRS
  for (uint k = 0u; k < samples; k += 2u) {
    LightSample first = nextLightSample(cursor, context, pixelSample, vertexDepth);
    LightSample second = first;  // past the last sample: not traced, adds nothing
    second.reflected = vec3(0.0);
    bool hasSecond = k + 1u < samples;
    if (hasSecond) second = nextLightSample(cursor, context, pixelSample, vertexDepth);
    Transmittance firstVisibility;
    Transmittance secondVisibility;
    lightVisibilityPair(first.shadowRay, shadowRayTraced(first, negligible) ? first.tMax : -1.0,
                        second.shadowRay,
                        shadowRayTraced(second, negligible) ? second.tMax : -1.0, throughGlass,
                        firstVisibility, secondVisibility);
    addLightSample(sums, context, k, sampleContribution(first, negligible, firstVisibility));
    if (hasSecond) {
      addLightSample(sums, context, k + 1u,
                     sampleContribution(second, negligible, secondVisibility));
    }
  }
#else
  for (uint k = 0u; k < samples; ++k) {
    LightSample lit = nextLightSample(cursor, context, pixelSample, vertexDepth);
    Transmittance visibility = Transmittance(0.0);
    if (shadowRayTraced(lit, negligible)) {
      visibility = lightVisibility(lit.shadowRay, lit.tMax, throughGlass);
    }
    addLightSample(sums, context, k, sampleContribution(lit, negligible, visibility));
  }
#endif
#ifdef RT_LIGHT_REPLICAS
  return sums.replicas / float(RT_REPLICAS);
#else
  return localLight(context, shadedDirect(context, sums.current));
#endif
}

#endif
