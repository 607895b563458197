// The one way the loaders read a file (scene JSON, PLY, glTF and its
// buffers, OBJ, MTL): whole, and only a regular file of at most
// kMaxInputFileBytes, so a device, a folder or a multi-gigabyte file is a
// clear message instead of a hang or an exhausted machine.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt {

constexpr uint64_t kMaxInputFileBytes = uint64_t(1) << 30;

// What keeps `file` from being read ("cannot open: No such file or
// directory", "file is 2048 MiB, more than the 1024 MiB allowed", ...), or
// "" with its bytes in `bytes`.
std::string readFileBytes(const std::filesystem::path& file, std::string& bytes);
std::string readFileBytes(const std::filesystem::path& file, std::vector<unsigned char>& bytes);

// The same, throwing rt::Error "<file>: <problem>".
std::string readFileOrThrow(const std::filesystem::path& file);

// A path as a model file writes it (an OBJ's mtllib and map_Kd, a PLY's
// TextureFile), with the backslashes of files written on Windows read as
// slashes.
std::filesystem::path portablePath(std::string written);

}  // namespace rt
