// Reflection and refraction at smooth dielectric interfaces.
#ifndef RT_OPTICS_GLSL
#define RT_OPTICS_GLSL

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

#endif
