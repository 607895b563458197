// Radiance along a camera ray. One loop serves both shaded modes:
//  - Phong: the Whitted ray tree of mirror reflection and refraction
//    (nbounces deep), walked depth first with an explicit stack (GLSL has no
//    recursion), plus `distributedBounces` sampled diffuse bounces;
//  - path tracer: the same continuations, but the stack holds one ray, so
//    each hit follows one of them, chosen with probability proportional to
//    its weight (Monte Carlo path tracing).
// Direct light comes from next-event estimation at every hit; emitted light
// is counted where no earlier estimate covered it (camera rays, and rays
// after a mirror or refraction), so no light is counted twice.
#ifndef RT_INTEGRATOR_GLSL
#define RT_INTEGRATOR_GLSL

#include "gpu_types.h"
#include "math.glsl"
#include "frame.glsl"
#include "rng.glsl"
#include "camera.glsl"
#include "geometry.glsl"
#include "surface.glsl"
#include "textures.glsl"
#include "optics.glsl"
#include "shading.glsl"

// The pending rays of the ray tree; the host sizes it per scene (Features).
#ifndef RT_WHITTED_STACK_SIZE
#define RT_WHITTED_STACK_SIZE 1
#endif

struct PendingRay {
  Ray ray;
  vec3 weight;
  uint depth;          // hits before this ray's origin (0: camera ray)
  uint diffuseDepth;   // of which sampled diffuse bounces
  bool countsEmission;  // no direct-light estimate covered what this ray hits
};

struct RayStack {
  PendingRay entries[RT_WHITTED_STACK_SIZE];
  uint size;
};

// Up to three continuations of one hit, in named slots rather than an
// array: the count differs between lanes, and a SIMD driver writes an array
// element at a per-lane index lane by lane (twelve scalars a ray), where a
// slot is written with one select per scalar for all lanes.
struct Continuations {
  PendingRay first;
  PendingRay second;
  PendingRay third;
  uint count;
};

void appendContinuation(inout Continuations next, PendingRay ray) {
  if (next.count == 0u) {
    next.first = ray;
  } else if (next.count == 1u) {
    next.second = ray;
  } else {
    next.third = ray;
  }
  ++next.count;
}

PendingRay continuationAt(Continuations next, uint index) {
  if (index == 0u) return next.first;
  return index == 1u ? next.second : next.third;
}

// A branch lighter than the bailout is dropped: at POV-Ray's 1/255 (the
// default) it cannot change an 8-bit pixel by more than its radiance in
// steps of 1/255, and the lanes of a vector drop the same faint glass
// branches together (README "Speed vs accuracy").
void addContinuation(inout Continuations next, PendingRay ray) {
  if (!(maxComponent(ray.weight) >= sceneInfo.branchBailout)) return;
  appendContinuation(next, ray);
}

#ifdef RT_ROULETTE_WEIGHT
// Russian roulette (RenderSettings::rouletteWeight): a continuation lighter
// than RT_ROULETTE_WEIGHT survives with probability weight / RT_ROULETTE_WEIGHT
// and then carries RT_ROULETTE_WEIGHT, so the estimate stays unbiased while
// the faint deep branches of a glass tree are mostly not traced. `u` is one
// uniform number; continuations use it rotated by the golden ratio.
void rouletteContinuations(inout Continuations next, float u) {
  Continuations kept;
  kept.count = 0u;
  for (uint i = 0u; i < next.count; ++i) {
    PendingRay ray = continuationAt(next, i);
    float weight = maxComponent(ray.weight);
    if (weight < RT_ROULETTE_WEIGHT) {
      if (fract(u + 0.61803399 * float(i)) * RT_ROULETTE_WEIGHT >= weight) continue;
      ray.weight *= RT_ROULETTE_WEIGHT / weight;
    }
    appendContinuation(kept, ray);
  }
  next = kept;
}
#endif

// The vertex's pair of lobe numbers: x picks the continuation a full stack
// follows, y the Fresnel branch of the path tracer (and drives roulette).
// The path tracer and roulette read them at every hit; a Whitted tree only
// where a full stack must choose (nextContinuation), which is rare: drawn at
// every hit, the stratified samplers cost 3-9% of a Whitted render (bench/README.md).
#if defined(RT_FEATURE_PATH_TRACER) || defined(RT_ROULETTE_WEIGHT)
#define RT_LOBE_AT_EVERY_HIT
#endif
vec2 lobeChoice(uvec2 pixelSample, uint vertex) {
  return samplePair(frame.samplerKind, pixelSample.x, pixelSample.y, frame.samplesTotal,
                    vertexDimension(vertex, RT_VERTEX_DIM_LOBE), frame.seed);
}

// Hands the walk its next ray: the last continuation is followed at once
// (`follow`) and the others wait on the stack, the order in which popping
// them all would have taken them. Without room for all of them it follows
// one, chosen with probability proportional to its weight and reweighted,
// which keeps the estimate unbiased at any depth. A SIMD driver writes a
// per-lane stack slot lane by lane (a ray is twelve scalars), so the ray a
// walk goes on with never passes through the stack: a mirror bounce touches
// it not at all. Returns false when the walk has no continuation here.
bool nextContinuation(inout RayStack stack, Continuations next, vec2 choice, uvec2 pixelSample,
                      uint vertex, out PendingRay follow) {
  follow = next.first;
  if (next.count == 0u) return false;
  if (stack.size + next.count <= RT_WHITTED_STACK_SIZE) {
    for (uint i = 0u; i + 1u < next.count; ++i) {
      stack.entries[stack.size++] = continuationAt(next, i);
    }
    follow = continuationAt(next, next.count - 1u);
    return true;
  }
  float total = 0.0;
  for (uint i = 0u; i < next.count; ++i) total += maxComponent(continuationAt(next, i).weight);
  if (!(total > 0.0) || stack.size >= RT_WHITTED_STACK_SIZE) return false;
#ifdef RT_LOBE_AT_EVERY_HIT
  float threshold = choice.x * total;
#else
  float threshold = lobeChoice(pixelSample, vertex).x * total;
#endif
  uint chosen = next.count - 1u;
  float running = 0.0;
  for (uint i = 0u; i < next.count; ++i) {
    running += maxComponent(continuationAt(next, i).weight);
    if (threshold < running) {
      chosen = i;
      break;
    }
  }
  follow = continuationAt(next, chosen);
  follow.weight *= total / maxComponent(follow.weight);
  return true;
}

PendingRay childRay(SurfacePoint surface, vec3 direction, vec3 weight, PendingRay parent,
                    bool diffuse) {
  Ray ray = spawnRay(surface.position, surface.positionError, surface.geometricNormal, direction);
  return PendingRay(ray, weight, parent.depth + 1u, parent.diffuseDepth + (diffuse ? 1u : 0u),
                    !diffuse);
}

// Mirror and refraction continuations of a hit. `surface` faces the
// incoming ray; `entering` says whether that side is the outside (winding
// normal) of the surface. `fresnelChoice` picks reflection or refraction
// where the path tracer follows one of them. `baseColor`: the diffuse colour
// at the point, which tints transmitted light where the material says so.
void addSpecularContinuations(inout Continuations next, PendingRay parent, SurfacePoint surface,
                              bool entering, GpuMaterial material, vec3 baseColor,
                              float fresnelChoice) {
  vec3 d = parent.ray.direction;
  vec3 facing = surface.shadingNormal;
#ifdef RT_FEATURE_REFLECTION
  vec3 mirrorWeight = parent.weight * material.reflectivity;
#ifdef RT_FEATURE_TINTED_MIRRORS
  if ((material.flags & RT_MATERIAL_TINTED_MIRROR) != 0u) mirrorWeight *= material.specularColor;
#endif
#else
  vec3 mirrorWeight = vec3(0.0);
#endif
  vec3 mirrorDir = reflect(d, facing);
#ifdef RT_FEATURE_REFRACTION
  if (material.transmission > 0.0) {
    float eta = interfaceEta(material, entering);
    float cosIncident = dot(-d, facing);
    float cosTransmitted;
    float reflectance = dielectricReflectance(cosIncident, eta, cosTransmitted);
    vec3 transmitted = parent.weight * material.transmission;
    bool refracts = reflectance < 1.0;
#ifdef RT_FEATURE_PATH_TRACER
    // One of the two, by Fresnel: the weight stays that of the glass.
    refracts = refracts && fresnelChoice >= reflectance;
    reflectance = refracts ? 0.0 : 1.0;
#endif
    mirrorWeight += transmitted * reflectance;
    if (refracts) {
      vec3 refractDir = normalize(eta * d + (eta * cosIncident - cosTransmitted) * facing);
      if (isThinWall(material)) refractDir = d;  // its light leaves it as it came
      vec3 refracted = transmitted * (1.0 - reflectance);
#ifdef RT_FEATURE_TINTED_TRANSMISSION
      // The light that passes takes the colour; the Fresnel reflection does not.
      if ((material.flags & RT_MATERIAL_TINTED_TRANSMISSION) != 0u) refracted *= baseColor;
#endif
      addContinuation(next, childRay(surface, refractDir, refracted, parent, false));
    }
  }
#endif
  addContinuation(next, childRay(surface, mirrorDir, mirrorWeight, parent, false));
}

#ifdef RT_FEATURE_DIFFUSE_BOUNCES
// A diffuse bounce: cosine-weighted about the shading normal, so the
// Blinn-Phong diffuse term (kd times colour, cos and 1/pi cancelling the
// density) is the whole weight. Directions below the geometric surface are
// dropped.
void addDiffuseContinuation(inout Continuations next, PendingRay parent, ShadingContext context,
                            vec2 u) {
  vec3 n = context.surface.shadingNormal;
  vec3 tangent;
  vec3 bitangent;
  tangentFrame(n, tangent, bitangent);
  vec2 disc = concentricDisc(u);
  float up = sqrt(max(0.0, 1.0 - dot(disc, disc)));
  vec3 direction = normalize(disc.x * tangent + disc.y * bitangent + up * n);
  if (dot(direction, context.surface.geometricNormal) <= 0.0) return;
  vec3 albedo = context.material.kd *
                (context.coursework ? courseworkDiffuseTint(context) : context.color);
  addContinuation(next, childRay(context.surface, direction, parent.weight * albedo, parent, true));
}
#endif

// How deep each kind of continuation may go.
struct DepthLimits {
  uint specular;  // mirror/refraction bounces on a path (nbounces)
  uint diffuse;   // sampled diffuse bounces on a path
  uint total;
};

DepthLimits depthLimits() {
#ifdef RT_FEATURE_PATH_TRACER
  uint bounces = sceneInfo.maxBounces;
  return DepthLimits(bounces, bounces, bounces);
#else
  uint diffuse = sceneInfo.distributedBounces;
  return DepthLimits(sceneInfo.maxBounces, diffuse, sceneInfo.maxBounces + diffuse);
#endif
}

// A light contribution to the pixel. After a diffuse bounce its largest
// channel is held to sceneInfo.indirectClamp (`clampindirect`, RT_FAR: off):
// rare bright paths (light through glass or off a mirror onto a diffuse
// surface) then add bounded speckles instead of fireflies, at the price of
// darker caustics.
vec3 clampedContribution(vec3 contribution, PendingRay job) {
#ifdef RT_FEATURE_DIFFUSE_BOUNCES
  float limit = job.diffuseDepth > 0u ? sceneInfo.indirectClamp : RT_FAR;
  float largest = max(contribution.r, max(contribution.g, contribution.b));
  return largest > limit ? contribution * (limit / largest) : contribution;
#else
  return contribution;
#endif
}

// The material's diffuse colour at a surface point: its texture's where it
// has one, times the mesh's vertex colours where it has them.
vec3 diffuseColorOf(GpuMaterial material, SurfacePoint surface) {
  vec3 color = diffuseColorAt(material, surface.uv);
#ifdef RT_FEATURE_VERTEX_COLORS
  color *= surface.vertexColor;
#endif
  return color;
}

// Everything a path does at a hit: emitted and direct light, continuations.
// Returns true with `job` set to the ray the walk goes on with.
bool shadeHit(inout RayStack stack, inout vec3 radiance, inout PendingRay job, SurfaceHit hit,
              uvec2 pixelSample, DepthLimits limits) {
  GpuMaterial material = loadMaterial(hitMaterial(hit));
  SurfacePoint surface = surfaceAt(job.ray, hit, material);
  vec3 baseColor = diffuseColorOf(material, surface);
#ifdef RT_FEATURE_TRANSMISSION_TEXTURES
  applyTransmissionTexture(material, surface.uv);
#endif
#if defined(RT_FEATURE_METAL_ROUGH_TEXTURES) || defined(RT_FEATURE_TINTED_MIRRORS)
  applyMetalRough(material, surface.uv, baseColor);
#endif
  bool entering = dot(job.ray.direction, surface.geometricNormal) < 0.0;
  faceViewer(surface, -job.ray.direction);
#if defined(RT_FEATURE_AREA_LIGHTS) || defined(RT_FEATURE_GLOW)
  if (job.countsEmission) {
    vec3 emitted = emittedRadiance(material, hit, job.ray.direction, surface);
    radiance += clampedContribution(job.weight * emitted, job);
  }
#endif
  ShadingContext context = ShadingContext(surface, -job.ray.direction, material, baseColor,
                                          sceneInfo.shadingModel == RT_SHADING_COURSEWORK);
  uint vertex = job.depth;
  // With sampled diffuse bounces, light through glass arrives along them
  // (caustics); straight shadow rays through glass would count it twice.
  bool throughGlass = limits.diffuse == 0u;
  vec3 local = hitLocalLight(context, pixelSample, vertex, throughGlass, maxComponent(job.weight));
  radiance += clampedContribution(job.weight * local, job);
#if defined(RT_FEATURE_REFLECTION) || defined(RT_FEATURE_REFRACTION) || \
    defined(RT_FEATURE_DIFFUSE_BOUNCES)
  if (job.depth >= limits.total) return false;
#ifdef RT_LOBE_AT_EVERY_HIT
  vec2 choice = lobeChoice(pixelSample, vertex);
#else
  const vec2 choice = vec2(0.0);  // not read: nextContinuation draws it if needed
#endif
  Continuations next;
  next.count = 0u;
#if defined(RT_FEATURE_REFLECTION) || defined(RT_FEATURE_REFRACTION)
  if (job.depth - job.diffuseDepth < limits.specular) {
    addSpecularContinuations(next, job, surface, entering, material, baseColor, choice.y);
  }
#endif
#ifdef RT_FEATURE_DIFFUSE_BOUNCES
  if (job.diffuseDepth < limits.diffuse) {
    vec2 u = samplePair(frame.samplerKind, pixelSample.x, pixelSample.y, frame.samplesTotal,
                        vertexDimension(vertex, RT_VERTEX_DIM_BOUNCE), frame.seed);
    addDiffuseContinuation(next, job, context, u);
  }
#endif
#ifdef RT_ROULETTE_WEIGHT
  // choice.y picks by Fresnel only in the path tracer, which has no roulette.
  rouletteContinuations(next, choice.y);
#endif
  return nextContinuation(stack, next, choice, pixelSample, vertex, job);
#else
  return false;
#endif
}

// Radiance arriving along `primary` for sample pixelSample.y of pixel
// pixelSample.x.
vec3 traceRadiance(Ray primary, uvec2 pixelSample) {
  RayStack stack;
  stack.size = 0u;
  PendingRay job = PendingRay(primary, vec3(1.0), 0u, 0u, true);
  DepthLimits limits = depthLimits();
  vec3 radiance = vec3(0.0);
  bool pending = true;
  while (pending) {
    SurfaceHit hit;
    bool follows = false;
    if (!closestHit(job.ray, 0.0, RT_FAR, hit)) {
      radiance += clampedContribution(job.weight * sceneInfo.backgroundColor, job);
    } else if (sceneInfo.renderMode == RT_MODE_BINARY) {
      radiance += job.weight * sceneInfo.binaryHitColor;
    } else {
      follows = shadeHit(stack, radiance, job, hit, pixelSample, limits);
    }
    if (!follows) {
      pending = stack.size > 0u;
      if (pending) job = stack.entries[--stack.size];
    }
  }
  return radiance;
}

#endif
