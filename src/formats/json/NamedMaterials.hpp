// Materials defined once in a `materials` list and named by shapes
// (`"material": "mat1"`), with the textures they name from a `textures` list
// (isaacery's files; README "Student scenes").
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "formats/json/JsonReader.hpp"
#include "scene/Scene.hpp"

namespace rt {

// Scene::materials index of each named material.
using NamedMaterials = std::map<std::string, uint32_t, std::less<>>;

// Reads the `textures` and `materials` lists of `sceneObject` (either may be
// absent) into scene.materials and scene.textures.
NamedMaterials readNamedMaterials(JsonObject& sceneObject, const std::filesystem::path& sceneDir,
                                  Scene& scene);

// The material a shape names: an error naming the key when no material of
// that name was defined.
uint32_t namedMaterial(const JsonNode& name, const NamedMaterials& materials);

}  // namespace rt
