// Reading a .gltf or .glb file into a tinygltf model, with the checks that
// must happen before tinygltf sees the bytes: GLB framing, JSON nesting depth
// and size, file sizes, and extensions the file requires.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "formats/gltf/GltfTiny.hpp"

namespace rt::gltf {

// Extensions whose meaning the loader implements (or may safely ignore).
bool isSupportedExtension(const std::string& name);

// Parses the file (GLB is recognised by its magic, not by the extension).
// Buffers are loaded; images keep their encoded bytes in Image::image
// (as_is = true) or, for external files, only their uri. Throws rt::Error
// "<file>: <what>"; tinygltf's warnings are appended to `warnings`.
tinygltf::Model readModel(const std::filesystem::path& file, std::vector<std::string>& warnings);

}  // namespace rt::gltf
