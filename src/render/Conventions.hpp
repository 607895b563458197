// The lighting and display conventions of each scene family. Neither
// coursework wrote them down; family A's were fitted to the official renders
// (see README "Conventions" and tests/render/test_reference.cpp).
#pragma once

#include <cstdint>
#include <optional>

#include "gpu_types.h"
#include "io/Image.hpp"
#include "scene/Scene.hpp"

namespace rt {

enum class ShadingModel { Standard, Coursework };

struct LightingConventions {
  uint32_t falloff = RT_FALLOFF_NONE;  // RT_FALLOFF_*
  float lightScale = 1.0f;             // multiplies every light intensity
  ShadingModel shading = ShadingModel::Standard;
};

// `shading` overrides the family's shading model when given.
LightingConventions lightingConventionsFor(SceneFamily family,
                                           std::optional<ShadingModel> shading = std::nullopt);

// The path tracer is physically based in both families: lights fall off as
// I / (4 pi d^2) (I is the power, as family A has it) and shading is the
// per-channel Blinn-Phong (the coursework model's clamp is no BRDF).
LightingConventions pathTracerConventions();

// The conventions a scene renders with: its family's, or the path tracer's.
LightingConventions lightingConventionsFor(const Scene& scene,
                                           std::optional<ShadingModel> shading = std::nullopt);

// Tone mapping for PNG/PPM output, including the camera's exposure.
ToneMapping toneMappingFor(const Scene& scene);

}  // namespace rt
