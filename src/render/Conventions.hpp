// The lighting and display conventions of each scene family. Neither
// coursework wrote them down; they were fitted to the official renders (see
// README "Conventions" and tests/render/test_reference.cpp).
#pragma once

#include <cstdint>

#include "gpu_types.h"
#include "io/Image.hpp"
#include "scene/Scene.hpp"

namespace rt {

struct LightingConventions {
  uint32_t falloff = RT_FALLOFF_NONE;  // RT_FALLOFF_*
  float lightScale = 1.0f;             // multiplies every light intensity
};

LightingConventions lightingConventionsFor(SceneFamily family);

// Tone mapping for PNG/PPM output, including the camera's exposure.
ToneMapping toneMappingFor(const Scene& scene);

}  // namespace rt
