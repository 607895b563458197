// Shared pieces of the libFuzzer targets: a scratch folder in which the files
// the seed scenes reference can be found, and the checks every target makes
// on what a loader returns or throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/Scene.hpp"
#include "util/Error.hpp"

namespace rt::fuzz {

// The seed data (../shared beside the checkout), or empty when it is absent.
std::filesystem::path sharedDir();

// A fresh folder under $TMPDIR, removed when the process exits.
std::filesystem::path makeScratchDir(std::string_view purpose);

// Makes the files that the documents in `seedRoots` reference reachable from
// `placeDir` exactly as from the documents' own folders: every JSON string of
// every *.json/*.gltf file that names a regular file of at most `maxBytes`
// (relative to the document's folder or, as the scene loader also looks
// there, to its parent) gets a symbolic link at the same relative place
// below `placeDir`, as long as that stays inside `scratchRoot`.
void linkReferencedFiles(const std::vector<std::filesystem::path>& seedRoots,
                         const std::filesystem::path& placeDir,
                         const std::filesystem::path& scratchRoot, uintmax_t maxBytes);

// The input file of a target whose loader reads files: `fileName` in
// `inputDir` below a fresh scratch folder for `purpose`, with the files that
// the seed documents under the shared folders `seedFolders` reference (at
// most `maxLinkedBytes` each) linked around it as linkReferencedFiles does.
std::filesystem::path prepareInputFile(std::string_view purpose,
                                       const std::filesystem::path& inputDir,
                                       const std::vector<std::string>& seedFolders,
                                       uintmax_t maxLinkedBytes, const std::string& fileName);

// Writes `bytes` to `file` (replacing it); aborts on failure, since a target
// that cannot write its input would fuzz nothing.
void writeInput(const std::filesystem::path& file, const uint8_t* bytes, size_t size);

// A loader's error must be one line that starts with the file it names.
// Aborts (a finding) otherwise.
void checkErrorMessage(std::string_view message, std::string_view file);

// What every loaded mesh and scene must satisfy; aborts on a violation.
void checkMesh(const TriangleMesh& mesh);
void checkScene(const Scene& scene);

// Checks what `load()` returns with `check`, or the error it throws as a
// message naming `file`.
template <typename Load, typename Check>
void checkLoad(const Load& load, const Check& check, std::string_view file) {
  try {
    check(load());
  } catch (const Error& error) {
    checkErrorMessage(error.what(), file);
  }
}

}  // namespace rt::fuzz
