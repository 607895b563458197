// Blinn-Phong direct lighting from point lights, with shadow rays.
#ifndef RT_SHADING_GLSL
#define RT_SHADING_GLSL

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

// Fraction of a light's intensity that reaches the end of `ray` through
// transmissive surfaces. Shadow rays go straight (refraction does not bend
// them: caustics need the path tracer), losing the Fresnel reflectance and
// (1 - transmission) at each crossing; an opaque surface blocks all.
float shadowTransmittance(Ray ray, vec3 lightPosition) {
  float transmittance = 1.0;
  for (int crossing = 0; crossing < RT_MAX_SHADOW_CROSSINGS; ++crossing) {
    SurfaceHit hit;
    if (!closestHit(ray, 0.0, length(lightPosition - ray.origin), hit)) return transmittance;
    GpuMaterial blocker = materials[hitMaterial(hit)];
    float cosine = dot(ray.direction, hit.normal);
    float eta = cosine < 0.0 ? 1.0 / blocker.ior : blocker.ior;
    float cosTransmitted;
    float reflectance = dielectricReflectance(abs(cosine), eta, cosTransmitted);
    transmittance *= blocker.transmission * (1.0 - reflectance);
    if (transmittance < RT_MIN_BRANCH_WEIGHT) return 0.0;
    vec4 point = hitPoint(ray, hit);
    ray = spawnRay(point.xyz, point.w, hit.normal, ray.direction);
  }
  return 0.0;
}
#endif

// Share of a light that reaches p from `shadowRay`'s origin.
float lightVisibility(Ray shadowRay, vec3 lightPosition) {
#ifdef RT_FEATURE_REFRACTION
  return shadowTransmittance(shadowRay, lightPosition);
#else
  return occluded(shadowRay, 0.0, length(lightPosition - shadowRay.origin)) ? 0.0 : 1.0;
#endif
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

// Light reflected towards `toViewer` from a surface already facing the viewer.
vec3 directLighting(SurfacePoint surface, vec3 toViewer, GpuMaterial material) {
  bool coursework = sceneInfo.shadingModel == RT_SHADING_COURSEWORK;
  vec3 p = surface.position;
  vec3 normal = surface.shadingNormal;
  vec3 color = diffuseColorAt(material, surface.uv);
  vec3 radiance = vec3(0.0);
  for (uint i = 0u; i < sceneInfo.pointLightCount; ++i) {
    GpuPointLight light = pointLights[i];
    vec3 toLight = light.position - p;
    float distance = length(toLight);
    if (!(distance > 0.0)) continue;
    vec3 l = toLight / distance;
    float cosine = dot(normal, l);
    // Light behind the surface as seen from the viewer (by either normal).
    if (cosine <= 0.0 || dot(surface.geometricNormal, l) <= 0.0) continue;
    Ray shadowRay = spawnRay(p, surface.positionError, surface.geometricNormal, l);
    float visibility = lightVisibility(shadowRay, light.position);
    if (visibility <= 0.0) continue;
    vec3 halfway = normalize(l + toViewer);
    // pow(0, 0) is undefined in GLSL (exp2(0 * log2(0)) = NaN on some
    // drivers): exponent 0 is the constant lobe 1.
    float highlight = material.specularExponent > 0.0
                          ? pow(max(dot(normal, halfway), 0.0), material.specularExponent)
                          : 1.0;
    vec3 diffuse = material.kd * light.diffuseIntensity * cosine;
    vec3 specular = material.ks * light.specularIntensity * highlight;
    if (!coursework) {
      diffuse *= color;
      specular *= material.specularColor;
    }
    radiance += visibility * lightAttenuation(distance) * (diffuse + specular);
  }
  // The coursework model clamps the light reaching the eye first, then tints
  // it (highlights included) by the normalised diffuse colour, or by the
  // texture colour as it is.
  if (!coursework) return radiance;
  return (isTextured(material) ? color : courseworkTint(color)) * min(radiance, vec3(1.0));
}

#endif
