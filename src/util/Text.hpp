// Small text helpers every stage uses: case-insensitive names and file
// extensions (scene keys, shape types, ".GLB" and ".obj").
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace rt {

// ASCII lower case (scene files are ASCII where it matters).
std::string lowercase(std::string text);

// The file's extension, lower-cased, with its dot (".gltf"); "" if none.
std::string lowerExtension(const std::filesystem::path& file);

// Whether the file's extension is one of `extensions` (lower case, with the
// dot), in any case: hasExtension("A.GLB", {".gltf", ".glb"}).
bool hasExtension(const std::filesystem::path& file,
                  std::initializer_list<std::string_view> extensions);

}  // namespace rt
