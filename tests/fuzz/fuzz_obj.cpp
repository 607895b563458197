// libFuzzer target: the OBJ loader, from bytes. An input may carry its
// material library after a line "#--mtl--", so that the MTL reader is
// fuzzed together with the OBJ that uses it.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.hpp"
#include "formats/obj/ObjLoader.hpp"

namespace {
constexpr std::string_view kName = "fuzz.obj";
constexpr std::string_view kMtlSeparator = "\n#--mtl--\n";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const size_t split = bytes.find(kMtlSeparator);
  const std::string_view obj = bytes.substr(0, split);
  const std::string_view mtl = split == std::string_view::npos
                                   ? std::string_view{}
                                   : bytes.substr(split + kMtlSeparator.size());
  rt::fuzz::checkLoad([&] { return rt::parseObjPart(obj, mtl, kName, rt::WorldTransform(1.0)); },
                      rt::fuzz::checkScene, kName);
  return 0;
}
