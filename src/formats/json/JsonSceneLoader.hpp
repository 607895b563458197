// Reads the coursework's JSON scene files (both families, plus the students'
// extension keys described in shared/scene-format/README.md) into rt::Scene.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "scene/Scene.hpp"

namespace rt {

// Loads a JSON scene file. Throws rt::Error with ONE line:
//   "<file>: <json.path>: <what is wrong>", e.g.
//   "scenes/x.json: scene.shapes[3].material.kd: expected a number, got string";
//   "<file>: byte <offset>: <parser message>" for JSON syntax errors;
//   "<file>: cannot open: <strerror>" for unreadable or missing files.
// Unknown and ignored keys never fail the load; they are listed in Scene::warnings.
Scene loadJsonScene(const std::filesystem::path& file);

// Same from an in-memory string; `file` is only used in messages and to
// resolve relative texture paths.
Scene parseJsonScene(std::string_view jsonText, const std::filesystem::path& file);

// Sampler names of the `sampler` key and --sampler: "random", "jittered"
// (also "jittering", "grid"), "sobol" (also "owen-sobol", "ld", "lowdiscrepancy",
// "low-discrepancy"); nullopt for anything else.
std::optional<SamplerKind> samplerKindNamed(const std::string& name);
// The canonical name ("random", "jittered", "sobol").
const char* samplerKindName(SamplerKind kind);

}  // namespace rt
