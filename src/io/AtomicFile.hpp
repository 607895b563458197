// Files appear whole or not at all: data goes to a temporary file in the
// same folder, which is renamed over the target only once fully written.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>

namespace rt {

void writeFileAtomically(const std::filesystem::path& target, const void* data, size_t bytes);

// Throws the error a later write of `target` would meet where it can be told
// now (its folder missing or read-only, or `target` a folder), so that a long
// render stops before it starts instead of after it ends.
void checkWritable(const std::filesystem::path& target);

// For writers that produce the file themselves (e.g. a library that takes a
// file name): `writeTo` writes the given temporary path; on success it is
// renamed to `target`, on failure (exception) it is removed.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path&)>& writeTo);

}  // namespace rt
