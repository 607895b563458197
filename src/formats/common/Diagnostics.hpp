// How every loader writes what it says about a file: one line,
// "<file>: <where>: <what>" ("<file>: <what>" when `where` is empty), where
// `where` is a JSON path ("scene.shapes[3].kd"), a glTF item
// ("meshes[0].primitives[1]") or a byte offset ("byte 212"). Errors are
// thrown as rt::Error; warnings are collected, each distinct line once, and
// the same warning at several places becomes one line that lists them
// ("<file>: scene.shapes[1].material.ks, scene.shapes[2].material.ks: missing; ...").
#pragma once

#include <cstddef>
#include <map>
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
  // The warnings so far, grouped by what they say, in the order first given.
  std::vector<std::string> takeWarnings();
  // A value the loader read ("camera.fov = 45"), for `raytracer check`.
  void noteRead(std::string_view where, std::string_view value);
  std::vector<std::string> takeReads() { return std::move(reads_); }

 private:
  struct Warning {
    std::string what;
    std::vector<std::string> places;  // each `where` once, in order
    std::set<std::string, std::less<>> seen;
  };
  std::string file_;
  std::vector<Warning> warnings_;
  std::map<std::string, size_t, std::less<>> byWhat_;  // index into warnings_
  std::vector<std::string> reads_;
};

// "byte <offset>", the `where` of a message about a place in a file's bytes.
std::string byteOffset(size_t offset);

}  // namespace rt
