// GLB files for the glTF tests: a document and its one binary buffer framed
// as glTF 2.0 section 4.4 says (a JSON chunk and a BIN chunk, each padded to
// four bytes).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rt::test {

inline void appendU32(std::string& out, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out += char((value >> shift) & 0xFF);
}

// The GLB bytes of `doc` with `bin` as its buffer 0 (which `doc` gets).
inline std::string glbBytes(nlohmann::json doc, const std::vector<uint8_t>& bin) {
  doc["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = doc.dump();
  while (json.size() % 4) json += ' ';
  std::string chunk(bin.begin(), bin.end());
  while (chunk.size() % 4) chunk += '\0';
  std::string out = "glTF";
  appendU32(out, 2);
  appendU32(out, uint32_t(12 + 8 + json.size() + 8 + chunk.size()));
  appendU32(out, uint32_t(json.size()));
  appendU32(out, 0x4E4F534Au);  // "JSON"
  out += json;
  appendU32(out, uint32_t(chunk.size()));
  appendU32(out, 0x004E4942u);  // "BIN\0"
  return out + chunk;
}

}  // namespace rt::test
