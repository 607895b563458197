// Typed, path-aware access to a parsed JSON document. Every failure throws one
// rt::Error line "<file>: <json.path>: <what is wrong>", and every object
// remembers which keys were read so the rest can be reported as unknown.
#pragma once

#include <cstdint>
#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "formats/common/Diagnostics.hpp"

namespace rt {

// ordered_json keeps the file's key order, so warnings come out in file order.
using Json = nlohmann::ordered_json;

// Shortest faithful text for a number in a message: integers without a
// fraction, everything else in %g form.
std::string formatNumber(double value);

// The member `key` of a raw JSON value, or null when the value is no object or
// lacks the key: for looking at a document before reading it (which family or
// layout it is), where nothing is reported and no key is marked as read.
const Json* findKey(const Json& object, std::string_view key);

class JsonObject;

// One JSON value plus its path from the document root, e.g. "scene.shapes[3].radius".
class JsonNode {
 public:
  JsonNode(const Json& value, std::string path, Diagnostics& diagnostics)
      : value_(&value), path_(std::move(path)), diagnostics_(&diagnostics) {}

  const Json& raw() const { return *value_; }
  const std::string& path() const { return path_; }
  // The path as messages give it: the document root has none, so it says so.
  std::string_view where() const {
    return path_.empty() ? std::string_view("(top level)") : std::string_view(path_);
  }
  Diagnostics& diagnostics() const { return *diagnostics_; }
  [[noreturn]] void fail(std::string_view what) const { diagnostics_->fail(where(), what); }
  void warn(std::string_view what) const { diagnostics_->warn(where(), what); }

  double number() const;     // any finite number
  float floatValue() const;  // finite and within float range
  float positiveFloat() const;
  float nonNegativeFloat() const;
  float floatInRange(float low, float high) const;   // inclusive
  int64_t integer() const;                           // integral value, 3.0 included, within +-2^53
  int64_t integer(int64_t low, int64_t high) const;  // inclusive range
  bool boolean() const;  // true/false, or 0/1 or "true"/"false" as some files write it
  std::string string() const;
  std::string nonEmptyString() const;
  glm::vec3 vec3() const;             // exactly three finite numbers
  glm::dvec3 point() const;           // a position: vec3()'s checks, kept in double precision
  glm::vec3 nonNegativeVec3() const;  // colours and intensities
  std::vector<JsonNode> array() const;
  JsonObject object() const;

 private:
  [[noreturn]] void failType(std::string_view expected) const;

  const Json* value_;
  std::string path_;
  Diagnostics* diagnostics_;
};

// A JSON object that tracks which of its keys the loader has looked at.
class JsonObject {
 public:
  explicit JsonObject(JsonNode node) : node_(std::move(node)) {}

  const std::string& path() const { return node_.path(); }
  std::string childPath(std::string_view key) const;
  Diagnostics& diagnostics() const { return node_.diagnostics(); }
  [[noreturn]] void fail(std::string_view what) const { node_.fail(what); }

  bool has(std::string_view key) const;          // does not mark the key as read
  const Json* peek(std::string_view key) const;  // the value, not marked read; nullptr if absent
  std::optional<JsonNode> optional(std::string_view key);
  JsonNode required(std::string_view key);
  // The single alias present among `keys`; an error when the file gives two.
  std::optional<JsonNode> optionalOneOf(std::initializer_list<std::string_view> keys);
  // Keys the format allows but that have no effect (renderer settings, hints).
  void ignore(std::initializer_list<std::string_view> keys);
  // A key we recognise but do not implement: read, and reported with `why`.
  void ignoreWithWarning(std::string_view key, std::string_view why);
  // Call once the loader is done with the object: every unread key becomes a warning.
  void reportUnknownKeys();

 private:
  JsonNode node_;
  std::set<std::string, std::less<>> read_;
};

}  // namespace rt
