// libFuzzer target: the JSON scene loader, from bytes. The scene is given a
// path in a scratch folder where the files the seed scenes reference (PLY
// meshes, textures) are linked at the same relative places, so inputs derived
// from the seeds also exercise mesh and texture loading.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.hpp"
#include "formats/json/JsonSceneLoader.hpp"

namespace {

namespace fs = std::filesystem;

// Larger referenced files would make every input that names them slow.
constexpr uintmax_t kMaxLinkedBytes = uintmax_t(1) << 20;

fs::path scenePath;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scenePath = rt::fuzz::prepareInputFile("scene", fs::path("scenes") / "examples", {"scene-format"},
                                         kMaxLinkedBytes, "fuzz.json");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rt::fuzz::checkLoad([&] { return rt::parseJsonScene(text, scenePath); }, rt::fuzz::checkScene,
                      scenePath.string());
  return 0;
}
