// libFuzzer target: the glTF loading path (.gltf JSON and .glb; the loader
// tells them apart by the GLB magic). The loader reads files, so each input
// is written to a scratch folder in which the buffers and images the seed
// models reference are linked under the names they use.
#include <cstddef>
#include <cstdint>

#include "FuzzSupport.hpp"
#include "scene/GltfLoader.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;

constexpr uintmax_t kMaxLinkedBytes = uintmax_t(4) << 20;

fs::path modelPath;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const fs::path root = rt::fuzz::makeScratchDir("gltf");
  const fs::path modelDir = root / "models" / "model";
  std::vector<fs::path> seedRoots;
  if (const fs::path shared = rt::fuzz::sharedDir(); !shared.empty()) {
    seedRoots = {shared / "assets" / "gltf", shared / "assets" / "gltf-invalid"};
  }
  rt::fuzz::linkReferencedFiles(seedRoots, modelDir, root, kMaxLinkedBytes);
  modelPath = modelDir / "input.gltf";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rt::fuzz::writeInput(modelPath, data, size);
  try {
    rt::fuzz::checkScene(rt::loadGltfScene(modelPath));
  } catch (const rt::Error& error) {
    rt::fuzz::checkErrorMessage(error.what(), modelPath.string());
  }
  return 0;
}
