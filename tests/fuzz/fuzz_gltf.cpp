// libFuzzer target: the glTF loading path (.gltf JSON and .glb; the loader
// tells them apart by the GLB magic). The loader reads files, so each input
// is written to a scratch folder in which the buffers and images the seed
// models reference are linked under the names they use.
#include <cstddef>
#include <cstdint>

#include "FuzzSupport.hpp"
#include "formats/gltf/GltfLoader.hpp"

namespace {

namespace fs = std::filesystem;

constexpr uintmax_t kMaxLinkedBytes = uintmax_t(4) << 20;

fs::path modelPath;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  modelPath = rt::fuzz::prepareInputFile("gltf", fs::path("models") / "model",
                                         {"assets/gltf", "assets/gltf-invalid"}, kMaxLinkedBytes,
                                         "input.gltf");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rt::fuzz::writeInput(modelPath, data, size);
  rt::fuzz::checkLoad([] { return rt::loadGltfScene(modelPath); }, rt::fuzz::checkScene,
                      modelPath.string());
  return 0;
}
