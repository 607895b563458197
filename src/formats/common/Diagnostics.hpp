// How every loader writes what it says about a file: one line,
// "<file>: <where>: <what>" ("<file>: <what>" when `where` is empty), where
// `where` is a JSON path ("scene.shapes[3].kd"), a glTF item
// ("meshes[0].primitives[1]") or a byte offset ("byte 212"). Errors are
// thrown as rt::Error; warnings are collected, each distinct line once.
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace rt {

class Diagnostics {
 public:
  explicit Diagnostics(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  std::string format(std::string_view where, std::string_view what) const;
  [[noreturn]] void fail(std::string_view where, std::string_view what) const;
  // A failure at byte `offset` of the file: "<file>: byte <offset>: <what>".
  [[noreturn]] void failAtByte(size_t offset, std::string_view what) const;
  void warn(std::string_view where, std::string_view what);
  // The warnings so far, in the order first given.
  std::vector<std::string> takeWarnings();

 private:
  std::string file_;
  std::vector<std::string> warnings_;
  std::set<std::string> seen_;
};

// "byte <offset>", the `where` of a message about a place in a file's bytes.
std::string byteOffset(size_t offset);

}  // namespace rt
