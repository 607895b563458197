// Files a JSON scene names (textures, meshes), found the way students' own
// programs found them: relative to the scene's folder, the folder above it,
// or as seen from a build folder inside the scene's folder.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "formats/json/JsonReader.hpp"
#include "scene/Scene.hpp"

namespace rt {

// The absolute folder of a scene file, against which the files it names are found.
std::filesystem::path absoluteFolderOf(const std::filesystem::path& file);

// The file a string node names, if it exists (backslashes read as folder
// separators); nullopt when it is in none of the places looked in. An
// absolute path from the author's machine is looked for by its tails in the
// scene's folder and the few above it, with a warning when found so.
std::optional<std::filesystem::path> findReferencedFile(const JsonNode& node,
                                                        const std::filesystem::path& sceneDir);

// "<kind> file not found: <path> (looked in ...)"; `kind` names the file.
std::string notFoundMessage(const JsonNode& node, const std::filesystem::path& sceneDir,
                            std::string_view kind);

// The texture file a string node names, into `out`: decoded once per scene;
// a file that is not there is a warning and the missing-texture squares
// (README "Student scenes"); one that cannot be decoded an error.
void readTextureFile(const JsonNode& node, const std::filesystem::path& sceneDir, Material& out,
                     Scene& scene);

}  // namespace rt
