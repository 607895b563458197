#include "render/Conventions.hpp"

namespace rt {

LightingConventions lightingConventionsFor(SceneFamily family) {
  switch (family) {
    case SceneFamily::PathOfLight: return {RT_FALLOFF_INVERSE_SQUARE, 1.0f / (4.0f * 3.14159265f)};
    case SceneFamily::Rendering: return {RT_FALLOFF_NONE, 1.0f};
  }
  return {};
}

ToneMapping toneMappingFor(const Scene& scene) {
  ToneMapping mapping;
  mapping.exposure = scene.camera.exposure;
  mapping.curve = ToneCurve::Clamp;
  mapping.srgbEncode = false;
  return mapping;
}

}  // namespace rt
