// Whitted ray tracing: the ray tree of mirror reflection and refraction is
// walked depth first with an explicit stack (GLSL has no recursion).
#ifndef RT_WHITTED_GLSL
#define RT_WHITTED_GLSL

struct PendingRay {
  Ray ray;
  vec3 weight;
  uint depth;
};

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

struct RayStack {
  PendingRay entries[RT_WHITTED_STACK_SIZE];
  uint size;
};

void pushIfVisible(inout RayStack stack, PendingRay child) {
  if (maxComponent(child.weight) < RT_MIN_BRANCH_WEIGHT) return;
  if (stack.size < RT_WHITTED_STACK_SIZE) stack.entries[stack.size++] = child;
}

// Pushes both children when the stack has room; otherwise follows one of
// them, chosen with probability proportional to its weight and reweighted,
// which keeps the estimate unbiased at any depth.
void pushChildren(inout RayStack stack, PendingRay first, PendingRay second, float choice) {
  if (stack.size + 2u <= RT_WHITTED_STACK_SIZE) {
    pushIfVisible(stack, first);
    pushIfVisible(stack, second);
    return;
  }
  float wFirst = maxComponent(first.weight);
  float wSecond = maxComponent(second.weight);
  float total = wFirst + wSecond;
  if (!(total > 0.0)) return;
  bool takeFirst = choice * total < wFirst;
  PendingRay chosen = takeFirst ? first : second;
  chosen.weight *= total / (takeFirst ? wFirst : wSecond);
  pushIfVisible(stack, chosen);
}

PendingRay childRay(SurfacePoint surface, vec3 direction, vec3 weight, uint depth) {
  Ray ray = spawnRay(surface.position, surface.positionError, surface.geometricNormal, direction);
  return PendingRay(ray, weight, depth);
}

// Adds the mirror and refraction children of a hit to the stack.
// `surface` faces the incoming ray; `entering` says whether that side is the
// outside (winding normal) of the surface.
void spawnSecondaryRays(inout RayStack stack, PendingRay parent, SurfacePoint surface,
                        bool entering, GpuMaterial material, float choice) {
  vec3 d = parent.ray.direction;
  vec3 facing = surface.shadingNormal;
  uint depth = parent.depth + 1u;
#ifdef RT_FEATURE_REFLECTION
  vec3 mirrorWeight = parent.weight * material.reflectivity;
#else
  vec3 mirrorWeight = vec3(0.0);
#endif
  vec3 mirrorDir = reflect(d, facing);
#ifdef RT_FEATURE_REFRACTION
  if (material.transmission > 0.0) {
    float eta = entering ? 1.0 / material.ior : material.ior;
    float cosIncident = dot(-d, facing);
    float cosTransmitted;
    float reflectance = dielectricReflectance(cosIncident, eta, cosTransmitted);
    mirrorWeight += parent.weight * material.transmission * reflectance;
    if (reflectance < 1.0) {
      vec3 refractDir = normalize(eta * d + (eta * cosIncident - cosTransmitted) * facing);
      vec3 refractWeight = parent.weight * material.transmission * (1.0 - reflectance);
      pushChildren(stack, childRay(surface, mirrorDir, mirrorWeight, depth),
                   childRay(surface, refractDir, refractWeight, depth), choice);
      return;
    }
  }
#endif
  pushIfVisible(stack, childRay(surface, mirrorDir, mirrorWeight, depth));
}


// Radiance arriving along `primary`; `branchKey` seeds the stochastic choice
// made only when the ray tree outgrows the stack.
vec3 traceRadiance(Ray primary, uvec3 branchKey) {
  RayStack stack;
  stack.size = 1u;
  stack.entries[0] = PendingRay(primary, vec3(1.0), 0u);
  vec3 radiance = vec3(0.0);
  while (stack.size > 0u) {
    PendingRay job = stack.entries[--stack.size];
    SurfaceHit hit;
    if (!closestHit(job.ray, 0.0, RT_FAR, hit)) {
      radiance += job.weight * sceneInfo.backgroundColor;
      continue;
    }
    if (sceneInfo.renderMode == RT_MODE_BINARY) {
      radiance += job.weight * sceneInfo.binaryHitColor;
      continue;
    }
    GpuMaterial material = materials[hitMaterial(hit)];
    SurfacePoint surface = surfaceAt(job.ray, hit);
    bool entering = dot(job.ray.direction, surface.geometricNormal) < 0.0;
    faceViewer(surface, -job.ray.direction);
    radiance += job.weight * directLighting(surface, -job.ray.direction, material);
#if defined(RT_FEATURE_REFLECTION) || defined(RT_FEATURE_REFRACTION)
    if (job.depth >= sceneInfo.maxBounces) continue;
    float choice =
        randomPair(branchKey.x, branchKey.y, RT_DIM_BRANCH + 2u * job.depth, branchKey.z).x;
    spawnSecondaryRays(stack, job, surface, entering, material, choice);
#endif
  }
  return radiance;
}

#endif
