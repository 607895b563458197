#include "encode/Conventions.hpp"

#include <glm/gtc/constants.hpp>

namespace rt {
namespace {

// Family B's renders show shadowed surfaces at 0.4 of their diffuse colour
// (a floor of colour (0.5, 0.8, 0.5) in shadow is (51, 81, 51)), whatever
// the lights' intensities.
constexpr float kCourseworkBAmbient = 0.4f;

}  // namespace

LightingConventions lightingConventionsFor(Conventions conventions,
                                           std::optional<ShadingModel> shading) {
  LightingConventions lighting;
  switch (conventions) {
    case Conventions::CourseworkA:
      // Intensities as given, spread over the sphere: I / (4 pi d^2). Fitted
      // to the official renders to within 1% (a 1% change costs 1.5 dB).
      lighting.falloff = RT_FALLOFF_INVERSE_SQUARE;
      lighting.lightScale = 1.0f / (4.0f * glm::pi<float>());
      lighting.shading = ShadingModel::Coursework;
      break;
    case Conventions::CourseworkB:
      lighting.ambient = glm::vec3(kCourseworkBAmbient);
      lighting.mirrorsReplaceLocalLight = true;
      break;
    case Conventions::Textbook:
      // Intensities below 1 and lights about a unit away: no falloff.
      break;
    case Conventions::Physical:
      // A light's intensity is 4 pi times its radiant intensity over pi: the
      // diffuse radiance kd Cd I cos / (4 pi d^2) is that of a Lambertian
      // surface of albedo kd Cd (its 1/pi) under a point light of I / 4 W/sr,
      // which is how the common scene writes the peers' 15 W/sr light (60).
      lighting.falloff = RT_FALLOFF_INVERSE_SQUARE;
      lighting.lightScale = 1.0f / (4.0f * glm::pi<float>());
      break;
  }
  if (shading) lighting.shading = *shading;
  return lighting;
}

LightingConventions pathTracerConventions() {
  LightingConventions lighting;
  lighting.falloff = RT_FALLOFF_INVERSE_SQUARE;
  lighting.lightScale = 1.0f / (4.0f * glm::pi<float>());
  return lighting;
}

LightingConventions lightingConventionsFor(const Scene& scene,
                                           std::optional<ShadingModel> shading) {
  if (scene.settings.mode == RenderMode::PathTracer) return pathTracerConventions();
  LightingConventions lighting = lightingConventionsFor(scene.conventions, shading);
  if (scene.ambientLight) lighting.ambient = *scene.ambientLight;
  return lighting;
}

ToneMapping toneMappingFor(const Scene& scene) {
  ToneMapping mapping;
  if (scene.conventions == Conventions::CourseworkB) {
    // Family B's `exposure` (0.1 in every official file) is not applied by
    // its renderers (times 0.1 every image would be nearly black), and they
    // write bytes as (unsigned char)(255 * c): the 0.25 background is 63.
    mapping.exposure = scene.settings.mode == RenderMode::PathTracer ? scene.camera.exposure : 1.0f;
    mapping.quantization = Quantization::Truncate;
  } else {
    mapping.exposure = scene.camera.exposure;
  }
  // Physical images are written as the peers write theirs: sRGB-encoded.
  mapping.srgbEncode = scene.conventions == Conventions::Physical;
  mapping.curve = scene.camera.toneCurve;
  return mapping;
}

}  // namespace rt
