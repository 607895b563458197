// State shared by the parts of the glTF loader: the parsed document, how
// messages are written, and the memory budget that bounds what a hostile
// file can make us allocate.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "formats/common/Diagnostics.hpp"
#include "formats/gltf/GltfTiny.hpp"

namespace rt::gltf {

// "meshes[3]" and friends, for messages.
std::string item(const char* array, int index);
std::string item(const char* array, size_t index);

// A URI's %XX escapes decoded (glTF URIs name relative files this way).
std::string percentDecoded(const std::string& uri);

class Context {
 public:
  Context(std::string fileName, const tinygltf::Model& model);

  const tinygltf::Model& model() const { return model_; }
  const std::string& fileName() const { return diagnostics_.file(); }

  // Throws rt::Error "<file>: <where>: <what>" (or "<file>: <what>").
  [[noreturn]] void fail(const std::string& where, const std::string& what) const;
  // A warning line of its own, "<file>: <where>: <what>"; repeats are dropped.
  void warn(const std::string& where, const std::string& what);
  // Something ignored at `where`; collected into one warning per feature,
  // "<file>: <feature> ignored (where1, where2, ...)".
  void ignored(const std::string& feature, const std::string& where);

  // Every allocation whose size the file decides is charged here first. The
  // budget is 64 MiB plus 8 times the bytes of all buffers: generous for real
  // files (quantized attributes, strips and mesh reuse expand the data by a
  // small factor) and a hard stop for files that reuse one accessor or node a
  // million times.
  void charge(uint64_t bytes, const std::string& where);

  // The warnings so far, the collected "ignored" ones last.
  std::vector<std::string> takeWarnings();

 private:
  Diagnostics diagnostics_;
  const tinygltf::Model& model_;
  uint64_t budgetLeft_ = 0;
  struct Places {
    std::vector<std::string> first;  // the first few, for the message
    std::string last;                // repeats of the same place count once
    size_t count = 0;
  };
  std::map<std::string, Places> ignored_;
};

}  // namespace rt::gltf
