// Reads the coursework's JSON scene files (both families, plus the students'
// extension keys described in shared/scene-format/README.md) into rt::Scene.
#pragma once

#include <filesystem>
#include <string_view>

#include "scene/Scene.hpp"

namespace rt {

// Loads a JSON scene file. Throws rt::Error with ONE line:
//   "<file>: <json.path>: <what is wrong>", e.g.
//   "scenes/x.json: scene.shapes[3].material.kd: expected a number, got string";
//   "<file>: byte <offset>: <parser message>" for JSON syntax errors;
//   "<file>: cannot open: <strerror>" for unreadable or missing files.
// Unknown and ignored keys never fail the load; they are listed in Scene::warnings.
Scene loadScene(const std::filesystem::path& file);

// Same from an in-memory string; `file` is only used in messages and to
// resolve relative texture paths.
Scene parseScene(std::string_view jsonText, const std::filesystem::path& file);

}  // namespace rt
