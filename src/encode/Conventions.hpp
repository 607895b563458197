// What each set of conventions (rt::Conventions) means for the renderer:
// how lights fall off, the shading model, ambient light, how mirrors mix
// with a surface's own shading, which way image right points, and how
// radiance becomes 8-bit pixels. Neither coursework wrote them down; family
// A's were fitted to the official renders, family B's to a student's
// renders of the official files (README "Conventions";
// tests/render/test_reference.cpp).
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
  // Light every hit receives from nowhere in particular: this times the
  // diffuse colour, added to the direct light (shadows included).
  glm::vec3 ambient{0.0f};
  // A hit's own (ambient + direct) light is clamped to 1 per channel, then
  // weighted by 1 - reflectivity - transmission, so a full mirror shows only
  // what it reflects. Without: the local light is added to the reflection.
  bool mirrorsReplaceLocalLight = false;
};

// `shading` overrides the conventions' shading model when given.
LightingConventions lightingConventionsFor(Conventions conventions,
                                           std::optional<ShadingModel> shading = std::nullopt);

// The path tracer is physically based under every set of conventions:
// lights fall off as I / (4 pi d^2) (I is the power, as family A has it),
// shading is the per-channel Blinn-Phong (the coursework model's clamp is
// no BRDF) and there is no ambient term.
LightingConventions pathTracerConventions();

// The lighting a scene renders with: its conventions', or the path tracer's.
LightingConventions lightingConventionsFor(const Scene& scene,
                                           std::optional<ShadingModel> shading = std::nullopt);

// Tone mapping for PNG/PPM output, including the camera's exposure.
ToneMapping toneMappingFor(const Scene& scene);

}  // namespace rt
