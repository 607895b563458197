// Reflection and refraction at smooth dielectric interfaces.
#ifndef RT_OPTICS_GLSL
#define RT_OPTICS_GLSL

#include "gpu_types.h"

// Unpolarised Fresnel reflectance of a dielectric interface. `eta` is
// n_incident / n_transmitted; returns 1 on total internal reflection.
float dielectricReflectance(float cosIncident, float eta, out float cosTransmitted) {
  float sin2Transmitted = eta * eta * max(0.0, 1.0 - cosIncident * cosIncident);
  cosTransmitted = 0.0;
  if (sin2Transmitted >= 1.0) return 1.0;
  cosTransmitted = sqrt(1.0 - sin2Transmitted);
  float rs = (eta * cosIncident - cosTransmitted) / (eta * cosIncident + cosTransmitted);
  float rp = (cosIncident - eta * cosTransmitted) / (cosIncident + eta * cosTransmitted);
  return 0.5 * (rs * rs + rp * rp);
}

// Whether light passes `material`'s surface unbent: a thin shell rather than
// the face of a solid (RT_MATERIAL_THIN_WALLED; built only where some scene
// material is one).
bool isThinWall(GpuMaterial material) {
#ifdef RT_FEATURE_THIN_WALLS
  return (material.flags & RT_MATERIAL_THIN_WALLED) != 0u;
#else
  return false;
#endif
}

// n_incident / n_transmitted where a ray meets `material`'s surface from its
// outside (`entering`) or its inside; a thin wall is met as from the outside
// on either side (no total internal reflection).
float interfaceEta(GpuMaterial material, bool entering) {
  return entering || isThinWall(material) ? 1.0 / material.ior : material.ior;
}

#endif
