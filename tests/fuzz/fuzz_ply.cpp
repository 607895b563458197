// libFuzzer target: the PLY loader, from bytes (ASCII and both binary
// byte orders; the header decides).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.hpp"
#include "formats/ply/PlyLoader.hpp"

namespace {
constexpr std::string_view kName = "fuzz.ply";
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rt::fuzz::checkLoad([&] { return rt::parsePly(bytes, kName); }, rt::fuzz::checkMesh, kName);
  return 0;
}
